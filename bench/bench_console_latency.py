#!/usr/bin/env python3
"""The web operator console's latency, runner -> console node -> websocket -> page in headless Chromium.

A private roscore, the real ``console`` node and a headless Chromium (Selenium) on its page. This process plays a
behavior runner: it latches flex_planner's ``~structure`` and a RUNNING status on ``/bench/behavior_runner/...``
and publishes BehaviorTransition messages at ``RATE_HZ`` (each with a distinct outcome, stamped when sent). A
MutationObserver in the page notes when each transition's line first appears in the transitions list (the page's
own rendering, unchanged); latency = that wall time - the send time (one clock: same machine).
Target (issue 26): p95 <= 100 ms at 100 transitions/s.

Then a 2000 x 2000 OccupancyGrid (5 cm cells: 100 m x 100 m of rooms, walls and unknown space) is published on
``/map`` while the page is open, timed until the page says it shows it ("map 2000 x 2000 ..."), and once more
for a page opened afterwards (its snapshot). Target: first shown <= 1 s.

``--soak MINUTES``: instead, the memory of the console node (resident set) and of the page (JS heap, DOM nodes)
sampled every minute while the fake runner sends 20 transitions, 20 activity updates and 5 log lines a second
(a busy behavior; the demo's runner sends far fewer) -- the issue's "flat over 30 min". ``--soak MINUTES --url
http://127.0.0.1:PORT/``: the same samples of a console already running (the demo's: ``tools/demo.sh --console PORT
--hold``, its real runners and the map view's overlays), found by its port; nothing is started but the browser.

Prints each figure with its ratio to the target and the machine's load average beside it (2 cores shared with
other work here: the figures move with the load), then PASS or FAIL (exit status 1). Needs Debian's chromium and
chromium-driver (tools/install.sh). ``bench/run.sh console_latency``.
"""

from __future__ import annotations

import io
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Tuple

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

import numpy as np  # noqa: E402
import rospy  # noqa: E402
from nav_msgs.msg import OccupancyGrid  # noqa: E402
from rospy.numpy_msg import numpy_msg  # noqa: E402
from std_msgs.msg import String  # noqa: E402

from flex_nav.behavior.structure import structure_json  # noqa: E402
from flex_nav.behavior.yaml_loader import load_behavior  # noqa: E402
from flex_nav.msg import BehaviorActivity, BehaviorLog, BehaviorStatus, BehaviorTransition  # noqa: E402
from flex_nav.testing.browser import HeadlessBrowser  # noqa: E402
from flex_nav.testing.private_master import PrivateMaster, free_port  # noqa: E402
from flex_nav.testing.process import ManagedProcess  # noqa: E402

RUNNER = "/bench/behavior_runner"
RATE_HZ = 100.0  # [1/s] transitions published
TRANSITIONS = 1000  # 10 s at RATE_HZ
WARMUP = 50  # first transitions not counted (connections settling)
TARGET_P95_MS = 100.0
MAP_CELLS = 2000  # per side
TARGET_MAP_S = 1.0
WAIT_S = 60.0  # [s] bound of every wait
SOAK_HZ = 20.0  # [1/s] transitions (and activity updates) during --soak; log lines at a quarter of it
SOAK_SAMPLE_S = 60.0  # [s] between two memory samples

# injected before the page's own script (CDP): when each transition's websocket message arrives, before the page
# handles it -- splits the latency into transport (runner -> console node -> websocket) and the page's drawing
ARRIVALS = """
window.benchArrived = {};
const Socket = window.WebSocket;
window.WebSocket = function (url, protocols) {
  const socket = new Socket(url, protocols);
  socket.addEventListener("message", (event) => {
    const m = /"outcome":"(o\\d+)"/.exec(event.data);
    if (m && !(m[1] in window.benchArrived)) window.benchArrived[m[1]] = performance.timeOrigin + performance.now();
  });
  return socket;
};
window.WebSocket.prototype = Socket.prototype;
for (const name of ["CONNECTING", "OPEN", "CLOSING", "CLOSED"]) window.WebSocket[name] = Socket[name];
"""

OBSERVER = """
window.benchSeen = {};
const note = (node) => {
  const m = / --(o\\d+)-->/.exec(node.textContent || "");
  if (m && !(m[1] in window.benchSeen)) window.benchSeen[m[1]] = performance.timeOrigin + performance.now();
};
new MutationObserver((records) => { for (const r of records) for (const n of r.addedNodes) note(n); })
  .observe(document.getElementById("transitions"), { childList: true });
window.benchMapAt = 0;
new MutationObserver(() => {
  if (!window.benchMapAt && document.getElementById("map-info").textContent.startsWith("map 2000 x 2000")) {
    window.benchMapAt = performance.timeOrigin + performance.now();
  }
}).observe(document.getElementById("map-info"), { childList: true, characterData: true, subtree: true });
return true;
"""


def load() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.2f} (1 min), {five:.2f} (5 min) on {os.cpu_count()} cores"


def rooms_map(cells: int, seed: int = 0) -> np.ndarray:
    """A cells x cells grid (int8, -1/0/100): rooms of 4 m with 10 cm walls and doors, unknown beyond a border."""
    rng = np.random.default_rng(seed)
    grid = np.zeros((cells, cells), dtype=np.int8)
    grid[::80, :] = 100
    grid[:, ::80] = 100
    grid[::80, 30:50] = 0  # doors
    grid[30:50, ::80] = 0
    grid[rng.integers(0, cells, 4000), rng.integers(0, cells, 4000)] = 100  # clutter
    grid[:, cells - 200:] = -1
    return grid


class FakeRunner:
    """The runner's operator topics as the console reads them."""

    def __init__(self) -> None:
        behaviors = REPO / "behaviors"
        text = structure_json(load_behavior("flex_planner", search_path=[behaviors]), [behaviors])
        self.structure = rospy.Publisher(f"{RUNNER}/structure", String, queue_size=1, latch=True)
        self.status = rospy.Publisher(f"{RUNNER}/status", BehaviorStatus, queue_size=1, latch=True)
        self.activity = rospy.Publisher(f"{RUNNER}/activity", BehaviorActivity, queue_size=1, latch=True)
        self.transitions = rospy.Publisher(f"{RUNNER}/transitions", BehaviorTransition, queue_size=200,
                                           tcp_nodelay=True)
        self.log = rospy.Publisher(f"{RUNNER}/log", BehaviorLog, queue_size=200)
        self.structure.publish(String(data=text))
        status = BehaviorStatus(behavior="flex_planner", code=BehaviorStatus.RUNNING, autonomy=3)
        status.header.stamp = rospy.Time.from_sec(time.time())
        self.status.publish(status)
        activity = BehaviorActivity(behavior="flex_planner", autonomy=3, active_paths=["/ReceiveGoal"])
        activity.header.stamp = status.header.stamp
        self.activity.publish(activity)

    def send(self, count: int, rate_hz: float) -> Dict[str, float]:
        sent: Dict[str, float] = {}
        start = time.monotonic()
        for i in range(count):
            delay = start + i / rate_hz - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            msg = BehaviorTransition(behavior="flex_planner", path="/ClearCostmaps", outcome=f"o{i}",
                                     target="ReceiveGoal")
            now = time.time()
            msg.header.stamp = rospy.Time.from_sec(now)
            sent[f"o{i}"] = now
            self.transitions.publish(msg)
        return sent


    def busy(self, seconds: float, rate_hz: float, first: int) -> int:
        """Transitions, activity updates and log lines for ``seconds`` [s]; the next transition number."""
        states = ("/ReceiveGoal", "/GetPath", "/ApprovePlan", "/Navigate")
        start, i = time.monotonic(), first
        while time.monotonic() - start < seconds:
            delay = start + (i - first) / rate_hz - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            stamp = rospy.Time.from_sec(time.time())
            msg = BehaviorTransition(behavior="flex_planner", path=states[i % 4], outcome=f"o{i}",
                                     target=states[(i + 1) % 4].lstrip("/"))
            msg.header.stamp = stamp
            self.transitions.publish(msg)
            activity = BehaviorActivity(behavior="flex_planner", autonomy=3, active_paths=[states[(i + 1) % 4]])
            activity.header.stamp = stamp
            self.activity.publish(activity)
            if i % 4 == 0:
                line = BehaviorLog(behavior="flex_planner", level=BehaviorLog.INFO, path=states[i % 4],
                                   text=f"log line {i}: " + "x" * 80)
                line.header.stamp = stamp
                self.log.publish(line)
            i += 1
        return i


def rss_mb(pid: int) -> float:
    """[MB] resident set of process ``pid`` (0 when it is gone)."""
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return 0.0


def console_pid(group: int) -> int:
    """The console node's Python process in the process group ``group`` (rosrun may run it as a child)."""
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if os.getpgid(int(entry.name)) != group:
                continue
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except (OSError, ProcessLookupError):
            continue
        if "python" in cmdline and "console" in cmdline and "rosrun" not in cmdline:
            return int(entry.name)
    return group


def soak(browser: HeadlessBrowser, busy: Callable[[float], None], pid: int, minutes: float) -> bool:
    """Memory samples every SOAK_SAMPLE_S while ``busy(seconds)`` keeps the console busy (or just waits); True when
    neither grew by more than 20 % (and 20 MB) from the second sample to the last."""
    page = ("return [performance.memory ? performance.memory.usedJSHeapSize / 1048576 : -1, "
            "document.getElementsByTagName('*').length];")
    samples: List[Tuple[float, float, float, int]] = []
    started = time.monotonic()
    print("minute  console RSS [MB]  page JS heap [MB]  page DOM nodes  load (1 min)")
    while True:
        heap, nodes = browser.script(page)
        elapsed = (time.monotonic() - started) / 60.0
        samples.append((elapsed, rss_mb(pid), float(heap), int(nodes)))
        print(f"{elapsed:6.1f}  {samples[-1][1]:16.1f}  {samples[-1][2]:17.1f}  {nodes:14d}  "
              f"{os.getloadavg()[0]:.2f}", flush=True)
        if elapsed >= minutes:
            break
        busy(min(SOAK_SAMPLE_S, (minutes - elapsed) * 60.0))
    base, last = samples[min(1, len(samples) - 1)], samples[-1]
    flat = all(last[k] <= max(base[k] * 1.2, base[k] + 20.0) for k in (1, 2))
    print(f"{last[0]:.1f} min; console {base[1]:.1f} -> {last[1]:.1f} MB, page heap "
          f"{base[2]:.1f} -> {last[2]:.1f} MB, DOM nodes {base[3]} -> {last[3]}: {'flat' if flat else 'GROWS'}")
    return flat


def console_by_port(port: int) -> int:
    """The console node's Python process serving ``port`` (its ``_port:=PORT`` argument); 0 when none."""
    for entry in Path("/proc").iterdir():
        try:
            args = (entry / "cmdline").read_bytes().split(b"\0") if entry.name.isdigit() else []
        except OSError:
            continue
        text = b" ".join(args).decode(errors="replace")
        if "python" in text and "console" in text and "rosrun" not in text and f"_port:={port}" in text:
            return int(entry.name)
    return 0


def soak_attached(url: str, minutes: float) -> int:
    """``--soak MINUTES --url URL``: sample a console that runs already; the exit status."""
    pid = console_by_port(int(url.rstrip("/").rsplit(":", 1)[1]))
    if not pid:
        print(f"no console node serving {url} found", file=sys.stderr)
        return 2
    with HeadlessBrowser(extra_arguments=("--enable-precise-memory-info",)) as browser:
        browser.driver.get(url)
        wait(browser, "return document.querySelectorAll('#graph svg g.node').length > 0;", "a runner's graph drawn")
        wait(browser, "return document.getElementById('map-info').textContent.startsWith('map ');", "the map shown")
        print(f"console node {pid} at {url}; the page shows the graph and the map ({load()})")
        flat = soak(browser, time.sleep, pid, minutes)
    print(f"{'PASS' if flat else 'FAIL'}: memory over {minutes:g} min ({load()})")
    return 0 if flat else 1


def wait(browser: HeadlessBrowser, script: str, what: str) -> Any:
    return browser.wait_for(lambda: browser.script(script), what, WAIT_S)


def transition_latency(browser: HeadlessBrowser, runner: FakeRunner) -> Tuple[np.ndarray, np.ndarray, int]:
    browser.script(OBSERVER)
    sent = runner.send(TRANSITIONS, RATE_HZ)
    last = f"o{TRANSITIONS - 1}"
    browser.wait_for(lambda: browser.script(f"return '{last}' in window.benchSeen;") or None,
                     "the last transition shown", WAIT_S)
    seen: Dict[str, float] = browser.script("return window.benchSeen;")
    arrived: Dict[str, float] = browser.script("return window.benchArrived || {};")
    counted = [f"o{i}" for i in range(WARMUP, TRANSITIONS)]
    latencies = np.array([seen[key] - sent[key] * 1e3 for key in counted if key in seen])
    transport = np.array([arrived[key] - sent[key] * 1e3 for key in counted if key in arrived])
    return latencies, transport, sum(1 for key in counted if key not in seen)


def map_first_shown(browser: HeadlessBrowser, url: str) -> Tuple[float, float, float]:
    """[s] publish -> shown in an open page, page opened -> shown, and the grid's serialisation alone (numpy_msg,
    as the console reads it)."""
    grid = rooms_map(MAP_CELLS)
    msg = numpy_msg(OccupancyGrid)()
    msg.header.frame_id = "map"
    msg.info.resolution = 0.05
    msg.info.width = msg.info.height = MAP_CELLS
    msg.info.origin.position.x = msg.info.origin.position.y = -50.0
    msg.info.origin.orientation.w = 1.0
    msg.data = grid.ravel()
    publisher = rospy.Publisher("/map", numpy_msg(OccupancyGrid), queue_size=1, latch=True)
    deadline = time.monotonic() + WAIT_S
    while publisher.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.05)
    published = time.time()
    publisher.publish(msg)
    wait(browser, "return window.benchMapAt > 0;", "the 2000 x 2000 map shown in the open page")
    in_open_page = browser.script("return window.benchMapAt;") / 1e3 - published
    opened = time.time()
    browser.driver.get(url)
    wait(browser, "const n = document.getElementById('map-info'); return n && n.textContent.startsWith('map 2000');",
         "the map shown in a page opened afterwards")
    new_page = time.time() - opened
    started = time.perf_counter()
    msg.serialize(io.BytesIO())
    return in_open_page, new_page, time.perf_counter() - started


def main() -> int:
    soak_minutes = float(sys.argv[sys.argv.index("--soak") + 1]) if "--soak" in sys.argv else 0.0
    if soak_minutes > 0 and "--url" in sys.argv:
        return soak_attached(sys.argv[sys.argv.index("--url") + 1], soak_minutes)
    with tempfile.TemporaryDirectory() as home:
        master = PrivateMaster(ros_home=Path(home) / "ros_home").start()
        os.environ.update(master.env)
        env = dict(master.env)
        env["PATH"] = f"{REPO / '.venv' / 'bin'}{os.pathsep}{env.get('PATH', '')}"
        env["ROS_PACKAGE_PATH"] = f"{REPO}{os.pathsep}{env.get('ROS_PACKAGE_PATH', '/opt/ros/noetic/share')}"
        port = free_port()
        console = ManagedProcess(["rosrun", "flex_nav", "console", f"_port:={port}", "_discovery_period_s:=0.2"],
                                 env=env, log_path=Path(home) / "console.log")
        try:
            rospy.init_node("bench_console_latency", disable_signals=True)
            runner = FakeRunner()
            url = f"http://127.0.0.1:{port}/"
            # precise: without it Chrome reports a coarse JS heap size, refreshed rarely
            with HeadlessBrowser(extra_arguments=("--enable-precise-memory-info",)) as browser:
                browser.driver.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": ARRIVALS})
                deadline = time.monotonic() + WAIT_S
                while True:
                    try:
                        browser.driver.get(url)
                        break
                    except Exception:
                        if time.monotonic() > deadline:
                            raise
                        time.sleep(0.5)
                wait(browser, "return document.querySelectorAll('#graph svg g.node').length > 0;",
                     "the runner's graph drawn")
                if soak_minutes > 0:
                    transitions = [0]

                    def busy(seconds: float) -> None:
                        transitions[0] = runner.busy(seconds, SOAK_HZ, transitions[0])

                    flat = soak(browser, busy, console_pid(console.popen.pid), soak_minutes)
                    print(f"{transitions[0]} transitions sent")
                    print(f"{'PASS' if flat else 'FAIL'}: memory over {soak_minutes:g} min ({load()})")
                    return 0 if flat else 1
                before = load()
                latencies, transport, lost = transition_latency(browser, runner)
                after = load()
                p50, p95 = np.percentile(latencies, 50), np.percentile(latencies, 95)
                print(f"transition -> page at {RATE_HZ:.0f}/s ({len(latencies)} counted, {lost} not shown): "
                      f"median {p50:.1f} ms, p95 {p95:.1f} ms, max {latencies.max():.1f} ms; "
                      f"ratio p95 / {TARGET_P95_MS:.0f} ms target = {p95 / TARGET_P95_MS:.2f}")
                if transport.size:
                    print(f"  of which to the page's websocket: median {np.percentile(transport, 50):.1f} ms, "
                          f"p95 {np.percentile(transport, 95):.1f} ms (the rest is the page's drawing)")
                print(f"  machine: {before} before, {after} after")
                in_open, new_page, serialise = map_first_shown(browser, url)
                print(f"{MAP_CELLS} x {MAP_CELLS} map first shown: {in_open * 1e3:.0f} ms from publish (open page), "
                      f"{new_page * 1e3:.0f} ms from opening a page; ratio to the {TARGET_MAP_S:.0f} s target = "
                      f"{max(in_open, new_page) / TARGET_MAP_S:.2f} (the grid's ROS serialisation alone: "
                      f"{serialise * 1e3:.0f} ms)")
                print(f"  machine: {load()}")
        finally:
            rospy.signal_shutdown("bench done")
            console.stop()
            master.stop()
    ok = lost == 0 and p95 <= TARGET_P95_MS and max(in_open, new_page) <= TARGET_MAP_S
    print(f"{'PASS' if ok else 'FAIL'}: p95 {p95:.1f} ms (<= {TARGET_P95_MS:.0f}), {lost} lost (0), map "
          f"{max(in_open, new_page):.2f} s (<= {TARGET_MAP_S:.0f})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
