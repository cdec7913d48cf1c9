// flex_nav operator console: one websocket to the console node, plain DOM, no framework, nothing from a CDN.
// Every text from the robots goes into the page with textContent; the SVG comes from the console's own Graphviz
// run and is parsed as XML, with anything active in it removed before it is shown.
"use strict";

(() => {
  const LEVELS = ["off", "low", "high", "full"];
  const LOG_ORDER = { DEBUG: 0, INFO: 1, HINT: 2, WARN: 3, ERROR: 4 };
  const KEEP_LINES = 1000;  // log lines and transitions kept per robot
  const SHOWN_LINES = 400;  // of those, the newest that match the filter are shown
  const FIRED_MS = 1500;  // how long the last transition's edge stays highlighted

  const $ = (id) => document.getElementById(id);
  const robots = new Map();  // name -> per-robot state
  let current = "";
  let socket = null;
  let client = 0;
  let nextId = 1;
  let retryMs = 500;
  const waiting = new Map();  // command ref -> feedback element
  let selectedPath = "";

  function robotState(name) {
    if (!robots.has(name)) {
      robots.set(name, { structure: null, svg: "", svgError: "", status: null, activity: null, lines: [],
        events: [], folded: new Set(), lastEdge: "", lastEdgeAt: 0, overlays: {}, userdata: null });
    }
    return robots.get(name);
  }

  // the server's id encoding of a path or outcome (flex_nav.console.graph)
  function encode(text) {
    let out = "";
    for (const ch of text) {
      if (/^[A-Za-z0-9]$/.test(ch)) out += ch;
      else if (ch === "/") out += "-";
      else out += "_" + ch.codePointAt(0).toString(16).padStart(6, "0");
    }
    return out;
  }
  const svgId = (path) => "st" + encode(path);
  const edgeId = (path, outcome) => `${svgId(path)}.e.${encode(outcome)}`;

  function el(tag, text, cls) {
    const node = document.createElement(tag);
    if (text !== undefined && text !== null) node.textContent = text;
    if (cls) node.className = cls;
    return node;
  }

  // --- connection -----------------------------------------------------------------------------------------------
  function connect() {
    const scheme = location.protocol === "https:" ? "wss://" : "ws://";
    socket = new WebSocket(scheme + location.host + "/ws");
    socket.onopen = () => { retryMs = 500; setConnection(true, "connected"); };
    socket.onclose = () => {
      setConnection(false, `disconnected; retrying in ${(retryMs / 1000).toFixed(1)} s`);
      setTimeout(connect, retryMs);
      retryMs = Math.min(retryMs * 2, 10000);
    };
    socket.onmessage = (event) => {
      let data;
      try { data = JSON.parse(event.data); } catch (err) { return; }
      handle(data);
    };
  }

  function setConnection(ok, text) {
    const node = $("connection");
    node.textContent = text;
    node.classList.toggle("offline", !ok);
  }

  function send(message, feedback) {
    const id = nextId++;
    const ref = `${client}:${id}`;
    if (feedback) {
      waiting.set(ref, feedback);
      showFeedback(feedback, "sending…", "pending");
    }
    if (!socket || socket.readyState !== WebSocket.OPEN) {
      if (feedback) showFeedback(feedback, "not connected to the console", "bad");
      return;
    }
    socket.send(JSON.stringify({ ...message, type: "command", id, robot: current }));
  }

  function showFeedback(node, text, kind) {
    node.textContent = text;
    node.className = "feedback " + (kind || "");
  }

  // --- events from the console --------------------------------------------------------------------------------
  function handle(data) {
    switch (data.type) {
      case "hello": client = data.client; break;
      case "snapshot":  // the console's whole state follows: history included, so drop ours
        for (const state of robots.values()) { state.lines = []; state.events = []; }
        break;
      case "robots": setRobots(data.robots); break;
      case "structure": onStructure(data); break;
      case "svg": onSvg(data); break;
      case "status": robotState(data.robot).status = data; if (data.robot === current) soon("status"); break;
      case "activity": robotState(data.robot).activity = data; if (data.robot === current) soon("activity"); break;
      case "transition": onTransition(data); break;
      case "userdata": robotState(data.robot).userdata = data; if (data.robot === current) soon("userdata"); break;
      case "log": addLine(data.robot, "lines", data); if (data.robot === current) soon("log"); break;
      case "feedback": onFeedback(data); break;
      case "sent": onSent(data); break;
      case "refused": onRefused(data); break;
      case "error": showError(data.message); break;
      case "map": onMap(data); break;
      case "map_patch": onMapPatch(data); break;
      case "overlay":
        robotState(data.robot).overlays[data.kind] = data;
        drawMapSoon();
        if (data.kind === "memory" && data.robot === current) showMemory();
        break;
      case "goal_sent": onGoalSent(data); break;
      case "forget_pending": onForgetPending(data); break;
      case "memory_forgotten": onMemoryForgotten(data); break;
      default: break;
    }
  }

  // Live events change the page at most once per frame: at 100 transitions/s, redrawing the lists per event
  // falls seconds behind (measured in bench/bench_console_latency.py).
  const dirty = new Set();
  let frame = 0;
  const RENDER = [["status", () => showStatus()], ["activity", () => showActivity()], ["log", () => showLog()],
    ["transitions", () => showTransitions()], ["fired", () => markFired()], ["userdata", () => showUserdata()]];

  function soon(what) {
    dirty.add(what);
    if (!frame) frame = requestAnimationFrame(flush);
  }

  function flush() {
    frame = 0;
    for (const [what, render] of RENDER) if (dirty.has(what)) render();
    dirty.clear();
  }

  function addLine(robot, key, item) {
    const list = robotState(robot)[key];
    list.push(item);
    if (list.length > KEEP_LINES) list.splice(0, list.length - KEEP_LINES);
  }

  function setRobots(names) {
    const select = $("robot");
    select.replaceChildren(...names.map((name) => { const o = el("option", name); o.value = name; return o; }));
    for (const name of [...robots.keys()]) if (!names.includes(name)) robots.delete(name);
    if (!names.includes(current)) current = names.length ? names[0] : "";
    select.value = current;
    showRobot();
  }

  function onStructure(data) {
    const state = robotState(data.robot);
    const changed = !state.structure || state.structure.behavior !== data.behavior;
    state.structure = data;
    state.svg = data.svg;
    state.svgError = data.error;
    if (changed) state.folded.clear();
    else if (state.folded.size) requestFolds(state, data.robot);  // the same behavior again: keep its folds
    if (data.robot === current) { if (changed) selectedPath = ""; showRobot(); }
  }

  function onSvg(data) {
    const state = robotState(data.robot);
    if (!state.structure || state.structure.behavior !== data.behavior) return;
    state.svg = data.svg;
    state.svgError = data.error;
    if (data.robot === current) { drawGraph(); showActivity(); }
  }

  function onTransition(data) {
    const state = robotState(data.robot);
    addLine(data.robot, "events", { kind: "transition", ...data });
    state.lastEdge = edgeId(data.path, data.outcome);
    state.lastEdgeAt = Date.now();
    if (data.robot === current) { soon("transitions"); soon("fired"); }
  }

  function onSent(data) {
    const node = waiting.get(data.ref);
    if (node) showFeedback(node, `sent: ${[data.command, ...data.args].join(" ")}`, "pending");
    addLine(data.robot, "events", { kind: "command", text: `→ ${[data.command, ...data.args].join(" ")}` });
    if (data.robot === current) soon("transitions");
  }

  function onRefused(data) {
    const node = waiting.get(data.ref);
    if (node) { showFeedback(node, `refused by the console: ${data.reason}`, "bad"); waiting.delete(data.ref); }
    else showError(data.reason);
  }

  function onFeedback(data) {
    const text = `${data.ok ? (data.pending ? "…" : "ok") : "refused"}: ${data.message}`;
    for (const ref of data.refs) {
      const node = waiting.get(ref);
      if (!node) continue;
      showFeedback(node, text, data.ok ? (data.pending ? "pending" : "ok") : "bad");
      if (!data.pending) waiting.delete(ref);
    }
    addLine(data.robot, "events", { kind: "feedback", ok: data.ok,
      text: `← ${[data.command, ...data.args].join(" ")}: ${text}` });
    if (data.robot === current) soon("transitions");
  }

  function showError(message) {
    const node = $("graph-error");
    node.textContent = message;
    node.hidden = !message;
  }

  // --- the selected robot ---------------------------------------------------------------------------------------
  function showRobot() {
    showMemory();
    drawGraph();
    showStatus();
    showActivity();
    showSelected();
    fillStartForm();
    showLog();
    showTransitions();
  }

  function showStatus() {
    const state = robots.get(current);
    const status = state && state.status;
    const node = $("status");
    node.textContent = status ? status.status + (status.outcome ? ` (${status.outcome})` : "") : "no status yet";
    node.className = "status " + (status ? status.status : "");
    $("behavior-name").textContent = state && state.structure ? state.structure.behavior || "no behavior" : "";
    $("status-reason").textContent = status ? status.reason : "";
    if (status) {
      $("autonomy-now").textContent = `autonomy ${LEVELS[status.autonomy] || status.autonomy}`;
      const level = LEVELS[status.autonomy];
      if (level && state.shownAutonomy !== level) {  // follow the runner's level when it changes, not on every status
        state.shownAutonomy = level;
        $("autonomy-level").value = level;
      }
    }
  }

  function sanitize(svg) {
    for (const bad of svg.querySelectorAll("script, foreignObject, iframe, a, image, use")) bad.remove();
    for (const node of [svg, ...svg.querySelectorAll("*")]) {
      for (const attr of [...node.attributes]) {
        if (/^on/i.test(attr.name) || /href$/i.test(attr.name)) node.removeAttribute(attr.name);
      }
    }
    return svg;
  }

  function drawGraph() {
    const box = $("graph");
    const state = robots.get(current);
    box.replaceChildren();
    showError(state && state.svgError ? `graph not drawn: ${state.svgError}` : "");
    if (!state || !state.svg) return;
    const doc = new DOMParser().parseFromString(state.svg, "image/svg+xml");
    const root = doc.documentElement;
    if (!root || root.nodeName !== "svg") { showError("the graph could not be read"); return; }
    box.appendChild(document.importNode(sanitize(root), true));
    const byId = new Map((state.structure ? state.structure.states : []).map((s) => [s.id, s]));
    for (const group of box.querySelectorAll("g.node, g.cluster")) {
      const info = byId.get(group.id);
      if (!info) continue;
      group.addEventListener("click", (event) => { event.stopPropagation(); select(info.path); });
      if (info.kind !== "state" && info.parent !== null) {
        group.addEventListener("dblclick", (event) => { event.stopPropagation(); toggleFold(info.path); });
      }
    }
    markFired();
  }

  function toggleFold(path) {
    const state = robots.get(current);
    if (!state) return;
    if (state.folded.has(path)) state.folded.delete(path); else state.folded.add(path);
    requestFolds(state, current);
  }

  function requestFolds(state, robot) {
    if (socket && socket.readyState === WebSocket.OPEN) {
      socket.send(JSON.stringify({ type: "fold", robot, folded: [...state.folded] }));
    }
  }

  function drawn(path, structure) {
    // the element drawn for path: itself, or (inside a folded container) the nearest container drawn
    const byPath = new Map(structure.states.map((s) => [s.path, s]));
    let at = byPath.get(path);
    while (at) {
      const found = document.getElementById(at.id);
      if (found) return found;
      at = at.parent === null ? null : byPath.get(at.parent);
    }
    return null;
  }

  function ancestors(path, structure) {
    const byPath = new Map(structure.states.map((s) => [s.path, s]));
    const out = [];
    let at = byPath.get(path);
    while (at && at.parent !== null) { out.push(at.parent); at = byPath.get(at.parent); }
    return out;
  }

  function showActivity() {
    const state = robots.get(current);
    const box = $("graph");
    for (const cls of ["active", "running", "waiting", "requested"]) {
      for (const node of box.querySelectorAll("." + cls)) node.classList.remove(cls);
    }
    for (const badge of box.querySelectorAll("text.badge")) badge.remove();
    const list = $("requests");
    list.replaceChildren();
    const activity = state && state.activity;
    const structure = state && state.structure;
    if (!activity || !structure || activity.behavior !== structure.behavior) {
      list.appendChild(el("li", "nothing waits", "none"));
      showSelected();
      return;
    }
    if (activity.autonomy !== undefined) $("autonomy-now").textContent = `autonomy ${LEVELS[activity.autonomy]}`;
    for (const path of activity.active) {
      const node = drawn(path, structure);
      if (node) node.classList.add("active");
      for (const above of ancestors(path, structure)) {
        const info = structure.states.find((s) => s.path === above);
        const cluster = info ? document.getElementById(info.id) : null;
        if (cluster && cluster.classList.contains("cluster")) cluster.classList.add("running");
      }
    }
    for (const request of activity.requests) {
      const node = drawn(request.path, structure);
      const needs = (LEVELS[request.required] || String(request.required)).toUpperCase();
      const why = request.reason === "lock" ? "waits for an unlock" : `needs autonomy above ${needs}`;
      if (node) {
        node.classList.add("waiting");
        badge(node, request.reason === "lock" ? "locked" : `needs > ${needs}`);
      }
      const edge = document.getElementById(edgeId(request.path, request.outcome));
      if (edge) edge.classList.add("requested");
      const item = el("li");
      item.appendChild(el("div", `${request.path} → ${request.outcome}`));
      item.appendChild(el("div", why, "needs"));
      const row = el("div", null, "row");
      const feedback = el("span", "", "feedback");
      if (request.reason !== "lock") {
        const approve = el("button", `approve ${request.outcome}`);
        approve.type = "button";
        approve.addEventListener("click", () => send({ command: "approve", path: request.path,
          outcome: request.outcome }, feedback));
        row.appendChild(approve);
      }
      const pick = el("button", "select");
      pick.type = "button";
      pick.addEventListener("click", () => select(request.path));
      row.appendChild(pick);
      row.appendChild(feedback);
      item.appendChild(row);
      list.appendChild(item);
    }
    if (!activity.requests.length) list.appendChild(el("li", "nothing waits", "none"));
    showSelected();
  }

  function badge(node, text) {
    const shape = node.querySelector("path, polygon, ellipse");
    if (!shape || typeof shape.getBBox !== "function") return;
    const box = shape.getBBox();
    const label = document.createElementNS("http://www.w3.org/2000/svg", "text");
    label.setAttribute("class", "badge");
    label.setAttribute("x", String(box.x + box.width + 3));
    label.setAttribute("y", String(box.y + 9));
    label.textContent = text;
    node.appendChild(label);
  }

  function markFired() {
    const state = robots.get(current);
    for (const node of $("graph").querySelectorAll(".fired")) node.classList.remove("fired");
    if (!state || !state.lastEdge || Date.now() - state.lastEdgeAt > FIRED_MS) return;
    const edge = document.getElementById(state.lastEdge);
    if (edge) edge.classList.add("fired");
    const edgeName = state.lastEdge;
    setTimeout(() => {
      const still = robots.get(current);
      if (still && still.lastEdge === edgeName && edge) edge.classList.remove("fired");
    }, FIRED_MS);
  }

  // --- the selected state -----------------------------------------------------------------------------------
  function select(path) {
    selectedPath = path;
    showSelected();
  }

  function showSelected() {
    const state = robots.get(current);
    const structure = state && state.structure;
    const info = structure ? structure.states.find((s) => s.path === selectedPath) : null;
    for (const node of $("graph").querySelectorAll(".selected")) node.classList.remove("selected");
    const box = $("selected");
    box.replaceChildren();
    $("selected-controls").hidden = !info;
    showUserdata();
    if (!info) { box.appendChild(el("p", "click a state in the graph", "none")); return; }
    const node = document.getElementById(info.id);
    if (node) node.classList.add("selected");
    const activity = state.activity;
    const active = !!activity && activity.behavior === structure.behavior &&
      activity.active.some((p) => p === info.path || ancestors(p, structure).includes(info.path));
    const list = el("dl");
    const rows = [["path", info.path], ["kind", info.kind.replace("_", " ") + (info.behavior ? ` (${info.behavior})` : "")],
      ["class", info.class], ["active", active ? "yes" : "no"],
      ["outcomes", info.outcomes.map((o) => `${o}${info.autonomy[o] ? ` [${LEVELS[info.autonomy[o]]}]` : ""}`).join(", ")]];
    for (const [key, value] of rows) { list.appendChild(el("dt", key)); list.appendChild(el("dd", value)); }
    box.appendChild(list);
    const buttons = $("force-buttons");
    buttons.replaceChildren();
    const feedback = document.querySelector('[data-feedback="state"]');
    for (const outcome of info.outcomes) {
      const button = el("button", `force ${outcome}`);
      button.type = "button";
      button.disabled = !active;
      button.title = active ? `make ${info.path} leave with ${outcome} now` : "only an active state can be forced";
      button.addEventListener("click", () => send({ command: "force", path: info.path, outcome }, feedback));
      buttons.appendChild(button);
    }
  }

  // the userdata the runner reports (each value already one line of text): the selected state's, or every active
  // state's when none is selected
  function showUserdata() {
    const state = robots.get(current);
    const box = $("userdata");
    box.replaceChildren();
    const data = state && state.userdata;
    const structure = state && state.structure;
    const reported = data && structure && data.behavior === structure.behavior ? Object.keys(data.states) : [];
    if (!reported.length) { box.appendChild(el("p", "no active state reports userdata", "none")); return; }
    // every active state: only those with keys (containers often have none)
    const paths = selectedPath ? reported.filter((p) => p === selectedPath)
      : reported.filter((p) => data.states[p].length);
    if (!paths.length) {
      box.appendChild(el("p", selectedPath ? `${selectedPath} is not active: no userdata`
        : "the active states have no userdata keys", "none"));
      return;
    }
    for (const path of paths) {
      box.appendChild(el("h3", path));
      const keys = data.states[path];
      if (!keys.length) { box.appendChild(el("p", "no userdata keys", "none")); continue; }
      const list = el("dl");
      for (const entry of keys) {
        const term = el("dt", entry.key);
        if (entry.role) term.appendChild(el("span", ` ${entry.role}`, "role"));
        const value = el("dd", entry.text, entry.set ? "" : "none");
        value.dataset.key = entry.key;
        list.appendChild(term);
        list.appendChild(value);
      }
      box.appendChild(list);
    }
    if (data.states_omitted) box.appendChild(el("p", `${data.states_omitted} more active states not shown`, "none"));
  }

  // --- the start form ---------------------------------------------------------------------------------------
  function fillStartForm() {
    const state = robots.get(current);
    const startable = state && state.structure ? state.structure.startable : [];
    const select = $("start-behavior");
    const before = select.value;
    select.replaceChildren(...startable.map((b) => { const o = el("option", b.name); o.value = b.name; return o; }));
    if (startable.some((b) => b.name === before)) select.value = before;
    fillParameters();
  }

  function startableEntry() {
    const state = robots.get(current);
    const name = $("start-behavior").value;
    return state && state.structure ? state.structure.startable.find((b) => b.name === name) : undefined;
  }

  function fillParameters() {
    const box = $("start-parameters");
    box.replaceChildren();
    const entry = startableEntry();
    if (!entry) return;
    if (entry.error) { box.appendChild(el("p", `parameters unreadable: ${entry.error}`, "field-error")); return; }
    for (const p of entry.parameters) {
      const label = el("label", `${p.name} (${p.type}${p.min !== null ? `, ≥ ${p.min}` : ""}` +
        `${p.max !== null ? `, ≤ ${p.max}` : ""}${p.has_default ? "" : ", required"})`);
      if (p.description) label.appendChild(el("span", p.description, "description"));
      let input;
      if (p.choices) {
        input = el("select");
        for (const choice of p.choices) {
          const option = el("option", String(choice));
          option.value = JSON.stringify(choice);
          input.appendChild(option);
        }
        if (p.has_default) input.value = JSON.stringify(p.default);
      } else if (p.type === "bool") {
        input = el("input");
        input.type = "checkbox";
        input.checked = p.has_default && p.default === true;
      } else if (p.type === "float" || p.type === "int") {
        input = el("input");
        input.type = "number";
        input.step = p.type === "int" ? "1" : "any";
        if (p.min !== null) input.min = String(p.min);
        if (p.max !== null) input.max = String(p.max);
        if (p.has_default) input.value = String(p.default);
      } else if (p.type === "list" || p.type === "dict") {
        input = el("textarea");
        input.rows = 2;
        input.placeholder = p.type === "list" ? "JSON list, e.g. [1, 2]" : 'JSON object, e.g. {"a": 1}';
        if (p.has_default) input.value = JSON.stringify(p.default);
      } else {
        input = el("input");
        input.type = "text";
        if (p.has_default) input.value = p.default;
      }
      input.dataset.parameter = p.name;
      const error = el("span", "", "field-error");
      error.dataset.errorFor = p.name;
      box.appendChild(label);
      box.appendChild(input);
      box.appendChild(error);
    }
  }

  function readParameter(p, input) {
    // [value, changed]; throws an Error with the reason for a value the browser can already tell is wrong
    if (p.choices) {
      const value = JSON.parse(input.value);
      return [value, !p.has_default || JSON.stringify(value) !== JSON.stringify(p.default)];
    }
    if (p.type === "bool") return [input.checked, !p.has_default || input.checked !== p.default];
    if (p.type === "float" || p.type === "int") {
      if (input.value.trim() === "") {
        if (p.has_default) return [p.default, false];
        throw new Error("a number is needed");
      }
      const value = Number(input.value);
      if (!Number.isFinite(value)) throw new Error(`${input.value} is not a number`);
      if (p.type === "int" && !Number.isInteger(value)) throw new Error(`${input.value} is not an integer`);
      return [value, !p.has_default || value !== p.default];
    }
    if (p.type === "list" || p.type === "dict") {
      if (input.value.trim() === "" && p.has_default) return [p.default, false];
      let value;
      try { value = JSON.parse(input.value); } catch (err) { throw new Error(`not JSON: ${err.message}`); }
      return [value, !p.has_default || JSON.stringify(value) !== JSON.stringify(p.default)];
    }
    return [input.value, !p.has_default || input.value !== p.default];
  }

  function submitStart(event) {
    event.preventDefault();
    const feedback = document.querySelector('[data-feedback="start"]');
    const entry = startableEntry();
    if (!entry) { showFeedback(feedback, "no behavior to start", "bad"); return; }
    const parameters = {};
    let wrong = false;
    for (const p of entry.parameters) {
      const input = document.querySelector(`[data-parameter="${CSS.escape(p.name)}"]`);
      const error = document.querySelector(`[data-error-for="${CSS.escape(p.name)}"]`);
      if (!input) continue;
      error.textContent = "";
      try {
        const [value, changed] = readParameter(p, input);
        if (changed) parameters[p.name] = value;
      } catch (err) {
        error.textContent = err.message;
        wrong = true;
      }
    }
    if (wrong) { showFeedback(feedback, "fix the marked parameters first", "bad"); return; }
    send({ command: "start", behavior: entry.name, autonomy: $("start-autonomy").value, parameters }, feedback);
  }

  // --- log and transitions ----------------------------------------------------------------------------------
  function showLog() {
    const state = robots.get(current);
    const list = $("log");
    const text = $("log-filter").value.trim().toLowerCase();
    const least = $("log-level").value;
    const lines = (state ? state.lines : []).filter((line) =>
      (!least || (LOG_ORDER[line.level] ?? 0) >= LOG_ORDER[least]) &&
      (!text || `${line.path} ${line.text}`.toLowerCase().includes(text)));
    const shown = lines.slice(-SHOWN_LINES);
    list.replaceChildren(...shown.map((line) => el("li",
      `${new Date(line.stamp * 1000).toISOString().slice(11, 23)} ${line.level} ${line.path || "(engine)"}: ` +
      line.text, line.level)));
    list.scrollTop = list.scrollHeight;
  }

  function showTransitions() {
    const state = robots.get(current);
    const list = $("transitions");
    const text = $("transition-filter").value.trim().toLowerCase();
    const forcedOnly = $("forced-only").checked;
    const items = (state ? state.events : []).filter((item) => {
      if (forcedOnly && !(item.kind === "transition" && item.forced)) return false;
      const words = item.kind === "transition" ? `${item.path} ${item.outcome} ${item.target}` : item.text;
      return !text || words.toLowerCase().includes(text);
    });
    list.replaceChildren(...items.slice(-SHOWN_LINES).map((item) => {
      if (item.kind !== "transition") return el("li", item.text, item.ok === false ? "refused" : "command");
      const needs = item.required ? ` [${LEVELS[item.required]}]` : "";
      return el("li", `${new Date(item.stamp * 1000).toISOString().slice(11, 23)} ${item.path} ` +
        `--${item.outcome}${needs}--> ${item.target}${item.forced ? " (forced)" : ""}`, item.forced ? "forced" : "");
    }));
    list.scrollTop = list.scrollHeight;
  }

  // --- the map ------------------------------------------------------------------------------------------------
  // The grid arrives as a PNG (row 0 = largest y) and is kept on an offscreen canvas; patches are drawn into it.
  // Everything else is drawn in map metres: canvas x = left + (x - ox) * k, canvas y = bottom - (y - oy) * k.
  // zoom (1 = the whole map fits) and centre [x, y] in map metres (null: the map's centre); wheel zooms about the
  // pointer, a drag with the right or middle button (or with Shift) pans, "fit" resets
  const map = { info: null, image: null, version: 0, view: null, drag: null, pan: null, pending: false, zoom: 1,
    centre: null };
  const ZOOM_STEP = 1.25;
  const MAX_ZOOM = 64;
  const ROBOT_COLOURS = ["#ef6c00", "#00838f", "#6d4c41", "#c2185b"];
  const MEMORY_COLOUR = "#8b0000";  // remembered heavy obstacles: dashed dark red

  function loadPng(png, done) {
    const img = new Image();
    img.onload = () => done(img);
    img.src = "data:image/png;base64," + png;
  }

  function onMap(data) {
    const old = map.info;
    if (!old || old.width !== data.width || old.height !== data.height || old.resolution !== data.resolution ||
        old.origin.join() !== data.origin.join()) { map.zoom = 1; map.centre = null; }  // another map: fit it
    map.info = data;
    map.version = data.version;
    loadPng(data.png, (img) => {
      if (map.info !== data) return;  // a newer map came meanwhile
      const canvas = document.createElement("canvas");
      canvas.width = data.width;
      canvas.height = data.height;
      canvas.getContext("2d").drawImage(img, 0, 0);
      map.image = canvas;
      const yawNote = data.origin[2] ? "; its origin's rotation is not shown" : "";
      $("map-info").textContent = `map ${data.width} x ${data.height} cells of ${Number(data.resolution.toPrecision(6))} m in ` +
        `${data.frame}${yawNote}`;
      drawMapSoon();
    });
  }

  function onMapPatch(data) {
    if (!map.info || data.version !== map.version + 1) return;  // a patch of another map: the next map event fixes
    map.version = data.version;
    loadPng(data.png, (img) => {
      if (!map.image) return;
      map.image.getContext("2d").drawImage(img, data.x, data.y);
      drawMapSoon();
    });
  }

  function drawMapSoon() {
    if (map.pending) return;
    map.pending = true;
    requestAnimationFrame(() => { map.pending = false; drawMap(); });
  }

  function mapView(canvas) {
    const info = map.info;
    const widthM = info.width * info.resolution;
    const heightM = info.height * info.resolution;
    const k = Math.min(canvas.width / widthM, canvas.height / heightM) * map.zoom;
    const [ox, oy] = info.origin;
    const [cx, cy] = map.centre || [ox + widthM / 2, oy + heightM / 2];
    return { k, left: canvas.width / 2 - (cx - ox) * k, bottom: canvas.height / 2 + (cy - oy) * k, ox, oy };
  }

  function onMapWheel(event) {
    if (!map.view) return;
    event.preventDefault();
    const canvas = $("map");
    const [px, py] = mapPoint(event);
    const [x, y] = toMap(map.view, px, py);
    map.zoom = Math.min(MAX_ZOOM, Math.max(1, map.zoom * (event.deltaY < 0 ? ZOOM_STEP : 1 / ZOOM_STEP)));
    const k = mapView(canvas).k;  // the new scale; the point under the pointer stays there
    map.centre = [x + (canvas.width / 2 - px) / k, y - (canvas.height / 2 - py) / k];
    drawMap();
  }

  function fitMap() {
    map.zoom = 1;
    map.centre = null;
    drawMapSoon();
  }

  const toCanvas = (v, x, y) => [v.left + (x - v.ox) * v.k, v.bottom - (y - v.oy) * v.k];
  const toMap = (v, cx, cy) => [v.ox + (cx - v.left) / v.k, v.oy + (v.bottom - cy) / v.k];

  function drawMap() {
    const canvas = $("map");
    if (canvas.width !== canvas.clientWidth || canvas.height !== canvas.clientHeight) {
      canvas.width = canvas.clientWidth;
      canvas.height = canvas.clientHeight;
    }
    const ctx = canvas.getContext("2d");
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    if (!map.info || !map.image) { map.view = null; canvas.dataset.view = ""; return; }
    const v = mapView(canvas);
    map.view = v;
    canvas.dataset.view = JSON.stringify(v);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(map.image, v.left, v.bottom - map.info.height * map.info.resolution * v.k,
      map.info.width * map.info.resolution * v.k, map.info.height * map.info.resolution * v.k);
    for (const state of robots.values()) drawMemory(ctx, v, state.overlays.memory);  // beneath the robots' drawings
    [...robots.keys()].forEach((name, index) => drawRobot(ctx, v, name, ROBOT_COLOURS[index % ROBOT_COLOURS.length]));
    // what was drawn, for tools and tests: per robot and kind, the pose, [remembered obstacles, their ids] or
    // [points, the last point]
    const drawn = {};
    for (const [name, state] of robots) {
      drawn[name] = {};
      for (const [kind, o] of Object.entries(state.overlays)) {
        if (kind === "pose") drawn[name][kind] = [o.x, o.y, o.footprint ? o.footprint.length : 0];
        else if (kind === "memory") drawn[name][kind] = [o.obstacles.length, o.obstacles.map((b) => b.id)];
        else drawn[name][kind] = [o.points.length, o.points[o.points.length - 1] || null];
      }
    }
    canvas.dataset.drawn = JSON.stringify(drawn);
    // the remembered obstacles drawn (every robot's): footprint [[x, y], ...] in map metres and text
    canvas.dataset.remembered = JSON.stringify(remembered().map(([, b]) => ({ id: b.id, footprint: b.footprint,
      text: b.text })));
    // the tracked people drawn (every robot's), [x, y] in map metres: where to look for them on the canvas
    canvas.dataset.people = JSON.stringify([...robots.values()].flatMap((state) =>
      state.overlays.people ? state.overlays.people.points.map(([x, y]) => [x, y]) : []));
    if (map.drag) {
      const [ax, ay] = toCanvas(v, map.drag.x, map.drag.y);
      ctx.strokeStyle = map.drag.kind === "goal" ? "#1565c0" : "#2e7d32";
      ctx.lineWidth = 3;
      ctx.beginPath();
      ctx.arc(ax, ay, 5, 0, 2 * Math.PI);
      ctx.moveTo(ax, ay);
      ctx.lineTo(map.drag.cx, map.drag.cy);
      ctx.stroke();
    }
  }

  function polyline(ctx, v, points, colour, width) {
    if (!points || points.length < 2) return;
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.beginPath();
    points.forEach(([x, y], i) => { const [cx, cy] = toCanvas(v, x, y); if (i) ctx.lineTo(cx, cy); else ctx.moveTo(cx, cy); });
    ctx.stroke();
  }

  // [robot, obstacle] of every robot's remembered obstacles
  const remembered = () => [...robots].flatMap(([name, state]) =>
    state.overlays.memory ? state.overlays.memory.obstacles.map((b) => [name, b]) : []);

  function drawMemory(ctx, v, memory) {
    if (!memory || !memory.obstacles.length) return;
    ctx.save();
    ctx.setLineDash([6, 4]);
    ctx.strokeStyle = MEMORY_COLOUR;
    ctx.fillStyle = "rgba(139, 0, 0, 0.15)";
    ctx.lineWidth = 2.5;
    for (const obstacle of memory.obstacles) {
      ctx.beginPath();
      obstacle.footprint.forEach(([x, y], i) => {
        const [cx, cy] = toCanvas(v, x, y);
        if (i) ctx.lineTo(cx, cy); else ctx.moveTo(cx, cy);
      });
      ctx.closePath();
      ctx.fill();
      ctx.stroke();
    }
    ctx.restore();
  }

  function inside(polygon, x, y) {  // even-odd rule
    let hit = false;
    for (let i = 0, j = polygon.length - 1; i < polygon.length; j = i++) {
      const [xi, yi] = polygon[i];
      const [xj, yj] = polygon[j];
      if ((yi > y) !== (yj > y) && x < xi + ((y - yi) * (xj - xi)) / (yj - yi)) hit = !hit;
    }
    return hit;
  }

  function hoverMemory(event) {  // the canvas's title: what the remembered obstacle under the pointer is
    const canvas = $("map");
    if (!map.view) { canvas.title = ""; return; }
    const [x, y] = toMap(map.view, ...mapPoint(event));
    const under = remembered().filter(([, b]) => inside(b.footprint, x, y));
    const title = under.map(([name, b]) => (robots.size > 1 ? `${name}: ` : "") + b.text).join("\n");
    if (canvas.title !== title) canvas.title = title;
  }

  function showMemory() {
    const state = robots.get(current);
    const memory = state && state.overlays.memory;
    const list = $("memory");
    if (!memory || !memory.obstacles.length) {
      list.replaceChildren(el("li", memory ? "nothing remembered" : "no obstacle memory seen", "none"));
      return;
    }
    const items = memory.obstacles.map((b) => el("li", b.text));
    if (memory.truncated) items.push(el("li", `and ${memory.truncated} more`, "none"));
    list.replaceChildren(...items);
  }

  function forgetMemory() {
    const feedback = document.querySelector('[data-feedback="memory"]');
    if (!socket || socket.readyState !== WebSocket.OPEN) { showFeedback(feedback, "not connected to the console", "bad"); return; }
    const id = nextId++;
    waiting.set(`${client}:${id}`, feedback);
    showFeedback(feedback, "sending…", "pending");
    socket.send(JSON.stringify({ type: "forget_memory", id, robot: current }));
  }

  function onForgetPending(data) {
    const node = waiting.get(data.ref);
    if (node) showFeedback(node, `asking ${data.robot}'s obstacle memory…`, "pending");
    addLine(data.robot, "events", { kind: "command", text: "→ forget remembered obstacles" });
    if (data.robot === current) soon("transitions");
  }

  function onMemoryForgotten(data) {
    const node = waiting.get(data.ref);
    const text = `${data.ok ? "ok" : "failed"}: ${data.message}`;
    if (node) { showFeedback(node, text, data.ok ? "ok" : "bad"); waiting.delete(data.ref); }
    addLine(data.robot, "events", { kind: "feedback", ok: data.ok, text: `← forget remembered obstacles: ${text}` });
    if (data.robot === current) soon("transitions");
  }

  function drawRobot(ctx, v, name, colour) {
    const o = robots.get(name).overlays;
    const mine = name === current;
    if (o.particles) {
      ctx.fillStyle = "rgba(142, 36, 170, 0.6)";
      for (const [x, y] of o.particles.points) { const [cx, cy] = toCanvas(v, x, y); ctx.fillRect(cx - 1, cy - 1, 2, 2); }
    }
    polyline(ctx, v, o.global_plan && o.global_plan.points, mine ? "#1565c0" : "rgba(21, 101, 192, 0.45)", 4);
    polyline(ctx, v, o.local_plan && o.local_plan.points, "#2e7d32", 1.5);  // thinner: the global plan shows beside
    if (o.scan) {
      ctx.fillStyle = "#d32f2f";
      for (const [x, y] of o.scan.points) { const [cx, cy] = toCanvas(v, x, y); ctx.fillRect(cx - 1.5, cy - 1.5, 3, 3); }
    }
    if (o.people) {  // tracked people: a 0.25 m disc facing the way they walk
      ctx.strokeStyle = "#e65100";
      ctx.fillStyle = "rgba(249, 168, 37, 0.55)";
      ctx.lineWidth = 1.5;
      for (const [x, y, yaw] of o.people.points) {
        const [cx, cy] = toCanvas(v, x, y);
        const r = Math.max(3, 0.25 * v.k);
        ctx.beginPath();
        ctx.arc(cx, cy, r, 0, 2 * Math.PI);
        ctx.fill();
        ctx.moveTo(cx, cy);
        ctx.lineTo(cx + Math.cos(yaw) * r * 1.5, cy - Math.sin(yaw) * r * 1.5);
        ctx.stroke();
      }
    }
    if (o.pose) {
      const [cx, cy] = toCanvas(v, o.pose.x, o.pose.y);
      const r = Math.max(3, o.pose.radius * v.k);
      ctx.fillStyle = colour + (mine ? "cc" : "77");
      ctx.strokeStyle = "#000";
      ctx.lineWidth = mine ? 2 : 1;
      ctx.beginPath();
      if (o.pose.footprint) {  // the robot's polygon, from its base frame into the map
        const c = Math.cos(o.pose.yaw);
        const s = Math.sin(o.pose.yaw);
        o.pose.footprint.forEach(([fx, fy], i) => {
          const [px, py] = toCanvas(v, o.pose.x + c * fx - s * fy, o.pose.y + s * fx + c * fy);
          if (i) ctx.lineTo(px, py); else ctx.moveTo(px, py);
        });
        ctx.closePath();
      } else {
        ctx.arc(cx, cy, r, 0, 2 * Math.PI);
      }
      ctx.fill();
      ctx.stroke();
      ctx.beginPath();
      ctx.moveTo(cx, cy);
      ctx.lineTo(cx + Math.cos(o.pose.yaw) * r * 1.6, cy - Math.sin(o.pose.yaw) * r * 1.6);
      ctx.stroke();
      ctx.fillStyle = "#000";
      ctx.font = "11px sans-serif";
      ctx.fillText(name.split("/").filter((p) => p)[0] || name, cx + r + 2, cy - r - 2);
    }
  }

  function mapPoint(event) {
    const canvas = $("map");
    const box = canvas.getBoundingClientRect();
    const cx = (event.clientX - box.left) * (canvas.width / box.width);
    const cy = (event.clientY - box.top) * (canvas.height / box.height);
    return [cx, cy];
  }

  function mapMode() {
    const checked = document.querySelector('input[name="map-mode"]:checked');
    return checked ? checked.value : "goal";
  }

  function onMapDown(event) {
    if (!map.view) return;
    if (event.button === 1 || event.button === 2 || (event.button === 0 && event.shiftKey)) {
      const [cx, cy] = mapPoint(event);
      const v = map.view;
      map.pan = { cx, cy, centre: toMap(v, $("map").width / 2, $("map").height / 2) };
      $("map").setPointerCapture(event.pointerId);
      return;
    }
    if (event.button !== 0) return;
    const [cx, cy] = mapPoint(event);
    const [x, y] = toMap(map.view, cx, cy);
    map.drag = { x, y, cx, cy, sx: cx, sy: cy, kind: mapMode() };
    $("map").setPointerCapture(event.pointerId);
    drawMapSoon();
  }

  function onMapMove(event) {
    if (!map.pan && !map.drag) hoverMemory(event);
    if (map.pan) {
      const [cx, cy] = mapPoint(event);
      const k = map.view ? map.view.k : 1;
      map.centre = [map.pan.centre[0] - (cx - map.pan.cx) / k, map.pan.centre[1] + (cy - map.pan.cy) / k];
      drawMapSoon();
      return;
    }
    if (!map.drag) return;
    [map.drag.cx, map.drag.cy] = mapPoint(event);
    drawMapSoon();
  }

  function onMapUp(event) {
    if (map.pan) { map.pan = null; return; }
    const drag = map.drag;
    map.drag = null;
    drawMapSoon();
    if (!drag || !map.view) return;
    const [cx, cy] = mapPoint(event);
    const dx = cx - drag.sx;
    const dy = drag.sy - cy;
    const yaw = Math.hypot(dx, dy) >= 5 ? Math.atan2(dy, dx) : 0;  // a click without a pull: heading east
    const feedback = document.querySelector('[data-feedback="map"]');
    const id = nextId++;
    waiting.set(`${client}:${id}`, feedback);
    if (!socket || socket.readyState !== WebSocket.OPEN) { showFeedback(feedback, "not connected to the console", "bad"); return; }
    showFeedback(feedback, "sending…", "pending");
    socket.send(JSON.stringify({ type: "goal", id, robot: current, kind: drag.kind, x: drag.x, y: drag.y, yaw }));
  }

  function onGoalSent(data) {
    const node = waiting.get(data.ref);
    const what = data.kind === "goal" ? "goal" : "initial pose";
    const text = `${what} sent to ${data.robot}: (${data.x.toFixed(2)}, ${data.y.toFixed(2)}) m, ` +
      `${(data.yaw * 180 / Math.PI).toFixed(0)} deg`;
    if (node) { showFeedback(node, text, "ok"); waiting.delete(data.ref); }
    addLine(data.robot, "events", { kind: "command", text: `→ ${text}` });
    if (data.robot === current) soon("transitions");
  }

  // --- wiring -------------------------------------------------------------------------------------------------
  function wire() {
    $("robot").addEventListener("change", (event) => {
      current = event.target.value; selectedPath = ""; showRobot(); drawMapSoon();
    });
    const canvas = $("map");
    canvas.addEventListener("pointerdown", onMapDown);
    canvas.addEventListener("pointermove", onMapMove);
    canvas.addEventListener("pointerup", onMapUp);
    canvas.addEventListener("pointercancel", () => { map.drag = null; map.pan = null; drawMapSoon(); });
    canvas.addEventListener("wheel", onMapWheel, { passive: false });
    canvas.addEventListener("contextmenu", (event) => event.preventDefault());
    $("map-fit").addEventListener("click", fitMap);
    $("memory-forget").addEventListener("click", forgetMemory);
    window.addEventListener("resize", drawMapSoon);
    if (typeof ResizeObserver === "function") new ResizeObserver(drawMapSoon).observe(canvas);  // layout changes
    const run = document.querySelector('[data-feedback="run"]');
    const state = document.querySelector('[data-feedback="state"]');
    for (const button of document.querySelectorAll("[data-command]")) {
      const command = button.dataset.command;
      button.addEventListener("click", () => {
        if (command === "autonomy") {
          send({ command, level: $("autonomy-level").value }, document.querySelector('[data-feedback="autonomy"]'));
        } else if (command === "lock" || command === "unlock") {
          send({ command, path: selectedPath }, state);
        } else {
          send({ command }, run);
        }
      });
    }
    $("start-behavior").addEventListener("change", fillParameters);
    $("start-form").addEventListener("submit", submitStart);
    $("log-filter").addEventListener("input", showLog);
    $("log-level").addEventListener("change", showLog);
    $("transition-filter").addEventListener("input", showTransitions);
    $("forced-only").addEventListener("change", showTransitions);
    $("unfold-all").addEventListener("click", () => {
      const current_state = robots.get(current);
      if (current_state && current_state.folded.size) {
        current_state.folded.clear();
        requestFolds(current_state, current);
      }
    });
    connect();
  }

  document.addEventListener("DOMContentLoaded", wire);
})();
