"""The console's web server (aiohttp): one page, its two static files and a websocket; no ROS here.

:class:`Console` keeps what each behavior runner last said (structure and its drawing, status, activity, the
recent log and transitions) and the connected pages. The ROS side (:mod:`flex_nav.nodes.console`) calls its
thread-safe ``submit_*`` methods from its callbacks; they hand the event to the server's event loop, which
broadcasts it. Commands from a page are validated (:mod:`flex_nav.console.commands`) and given to the ``send``
callable (the ROS side publishes them); refusals go back to that page with the reason.

Security (:class:`ServerConfig`): bound to 127.0.0.1 by default; any other address needs a token of at least
``MIN_TOKEN_CHARS`` characters. With a token, every HTTP request (the websocket handshake too) must carry it, in
the ``flex_nav_console`` cookie (set by opening ``/?token=...`` once, which then redirects to ``/``) or as
``Authorization: Bearer ...``; it is compared with :func:`hmac.compare_digest`. Without a token only loopback
``Host`` names are served (a DNS-rebinding page gets 403). The websocket handshake must come from the page's own
origin (``Origin`` equal to ``http://<Host>``). Every queue is bounded: a page that reads too slowly gets a fresh
snapshot instead of the backlog; incoming messages are limited to ``max_message_bytes``.

The websocket's JSON messages. From the page: ``{"type": "command", "id", "robot", "command", ...its fields}``
(:mod:`flex_nav.console.commands`) and ``{"type": "fold", "robot", "folded": [container paths]}``. To the page:
``hello`` (``client``: the page's number; its command references are ``"<client>:<id>"``), ``snapshot`` (the
console's whole state follows, history included), the events of :mod:`flex_nav.console.events`, ``userdata``
(:mod:`flex_nav.console.userdata`: the active states' userdata, each value as a line of text),
``snapshot_done``; ``sent`` / ``refused`` (``ref``, ``robot``, the runner's ``command`` and ``args`` / the
``reason`` and the ``field``) answering a command; ``svg`` (a fold's drawing); ``error`` (``message``).

The map view (:mod:`flex_nav.console.mapview`): ``map`` once (and again when its geometry changes), then
``map_patch`` for changed rectangles, and ``overlay`` per robot and kind; the page's ``{"type": "goal", ...}``
(a goal or an initial pose placed on the map) is checked by :func:`~flex_nav.console.mapview.check_goal` and
given to the ``send_goal`` callable, answered with ``goal_sent`` (``ref``, ``robot``, ``kind``, ``x``, ``y``,
``yaw``) or ``refused``.

The obstacle memory: the page's ``{"type": "forget_memory", "id", "robot"}`` asks the robot's global costmap to
forget every remembered obstacle (the ``forget_memory`` callable, run off the event loop and bounded by
``FORGET_TIMEOUT_S``; one request per robot at a time): answered at once with ``forget_pending`` (``ref``,
``robot``) or ``refused``, then with ``memory_forgotten`` (``ref``, ``robot``, ``ok``, ``message``: the costmap's
answer, or why it could not be asked, e.g. no such service when the memory is off).
"""

from __future__ import annotations

import asyncio
import collections
import contextlib
import dataclasses
import hmac
import ipaddress
import itertools
import json
import threading
from pathlib import Path
from typing import Any, Awaitable, Callable, Deque, Dict, List, Mapping, Optional, Sequence, Set, Tuple

from aiohttp import WSMsgType, web

from flex_nav.console.commands import RunnerCommand, refuse_choice, validate_command
from flex_nav.console.errors import CommandRefused, StructureError, UserdataError
from flex_nav.console.events import CommandTracker, known_ref, robots_event, structure_event
from flex_nav.console.graph import render_svg, to_dot
from flex_nav.console.mapview import GoalRequest, GridGeometry, MapPicture, check_goal
from flex_nav.console.model import BehaviorStructure
from flex_nav.console.userdata import userdata_event
from flex_nav.exceptions import ConfigError, FlexNavError, NotReadyError

WEB_DIR = Path(__file__).resolve().parent / "web"
STATIC_FILES = {"/": ("index.html", "text/html"), "/console.js": ("console.js", "text/javascript"),
                "/console.css": ("console.css", "text/css")}
COOKIE = "flex_nav_console"
MIN_TOKEN_CHARS = 16
LOOPBACK_NAMES = ("localhost", "127.0.0.1", "::1")
HISTORY = 200  # log lines and transitions kept per robot for a page that connects later
FORGET_TIMEOUT_S = 10.0  # [s] bound on a robot's answer to forget its remembered obstacles
MESSAGE_TYPES = ("command", "fold", "goal", "forget_memory")  # what a page may send
SECURITY_HEADERS = {
    "Content-Security-Policy": "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; "
                               "connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'",
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
    "Referrer-Policy": "no-referrer",
    "Cache-Control": "no-store",
}

Sender = Callable[[str, RunnerCommand], None]  # (runner name, command): publish it; FlexNavError if it cannot
Renderer = Callable[[BehaviorStructure, Sequence[str]], str]  # (structure, folded container paths) -> SVG
GoalSender = Callable[[GoalRequest], None]  # publish a checked goal or initial pose; FlexNavError if it cannot
MemoryForgetter = Callable[[str], Tuple[bool, str]]  # (runner name): its costmap's (success, message); FlexNavError


def is_loopback(host: str) -> bool:
    if host in LOOPBACK_NAMES:
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


@dataclasses.dataclass(frozen=True)
class ServerConfig:
    """Where and how the console serves; checked when made (ConfigError with the reason)."""

    host: str = "127.0.0.1"
    port: int = 8080
    token: str = ""
    max_clients: int = 16  # pages connected at once
    client_queue: int = 2000  # events waiting for one page before it is resynchronised
    max_message_bytes: int = 64 * 1024  # a message from a page

    def __post_init__(self) -> None:
        if not self.host:
            raise ConfigError("host must be an address to bind, e.g. 127.0.0.1")
        if not 0 <= self.port <= 65535:
            raise ConfigError(f"port {self.port} is not a TCP port (0..65535; 0 picks a free one)")
        if not is_loopback(self.host) and not self.token:
            raise ConfigError(f"host {self.host!r} is reachable from other machines: set a token "
                              f"(_token:=..., at least {MIN_TOKEN_CHARS} characters) or serve on 127.0.0.1")
        if self.token and len(self.token) < MIN_TOKEN_CHARS:
            raise ConfigError(f"the token has {len(self.token)} characters; use at least {MIN_TOKEN_CHARS} "
                              "(e.g. python3 -c 'import secrets; print(secrets.token_urlsafe(24))')")
        for name in ("max_clients", "client_queue", "max_message_bytes"):
            if getattr(self, name) < 1:
                raise ConfigError(f"{name} must be at least 1, got {getattr(self, name)}")


def token_matches(given: str, token: str) -> bool:
    """Constant-time comparison of a presented token with the console's."""
    return hmac.compare_digest(given.encode("utf-8", "replace"), token.encode("utf-8"))


def default_renderer(structure: BehaviorStructure, folded: Sequence[str]) -> str:
    return render_svg(to_dot(structure, frozenset(folded)))


@dataclasses.dataclass
class RobotView:
    """The console's picture of one runner."""

    structure: BehaviorStructure = dataclasses.field(default_factory=BehaviorStructure.empty)
    structure_text: str = ""  # the JSON it was read from
    structure_event: Optional[Dict[str, Any]] = None
    status: Optional[Dict[str, Any]] = None
    activity: Optional[Dict[str, Any]] = None
    history: Deque[Dict[str, Any]] = dataclasses.field(default_factory=lambda: collections.deque(maxlen=HISTORY))
    overlays: Dict[str, Dict[str, Any]] = dataclasses.field(default_factory=dict)  # kind -> latest overlay event
    userdata: Optional[Dict[str, Any]] = None  # the latest userdata event (flex_nav.console.userdata)

    def active(self) -> Optional[List[str]]:
        """The active paths last reported for the loaded behavior (None: not known)."""
        if self.activity is None or self.activity.get("behavior") != self.structure.behavior:
            return None
        return list(self.activity["active"])


class _Client:
    def __init__(self, number: int, queue_size: int) -> None:
        self.number = number
        self.queue: asyncio.Queue[Optional[str]] = asyncio.Queue(maxsize=queue_size)
        self.resyncs = 0

    def put(self, text: str) -> None:
        try:
            self.queue.put_nowait(text)
        except asyncio.QueueFull:  # too slow: drop the backlog, send a snapshot instead
            while not self.queue.empty():
                self.queue.get_nowait()
            self.resyncs += 1
            self.queue.put_nowait(None)


class Console:
    """The robots' latest state and the connected pages (see the module doc)."""

    def __init__(self, config: ServerConfig, send: Sender, render: Renderer = default_renderer,
                 send_goal: Optional[GoalSender] = None) -> None:
        self.config = config
        self.send = send
        self.send_goal: GoalSender = send_goal or _no_goals
        self.forget_memory: MemoryForgetter = _no_memory
        self._forgetting: Set[str] = set()  # robots asked to forget and not yet answered (event loop only)
        self._tasks: Set[asyncio.Task[None]] = set()  # running requests to forget (kept from the collector)
        self.render = render
        self.map = MapPicture()  # updated in the caller's thread (PNG work stays off the event loop)
        self._map_lock = threading.Lock()
        self.robots: Dict[str, RobotView] = {}
        self.tracker = CommandTracker()
        self.clients: Dict[int, _Client] = {}
        self._numbers = itertools.count(1)
        self._loop: Optional[asyncio.AbstractEventLoop] = None
        self._svg_cache: Dict[Tuple[str, str, Tuple[str, ...]], Tuple[str, str]] = {}
        self._pages = {path: ((WEB_DIR / name).read_bytes(), kind) for path, (name, kind) in STATIC_FILES.items()}
        self.dropped = 0  # events submitted before the loop ran or after it stopped
        self._lock = threading.Lock()

    # --- from any thread (the ROS callbacks) -------------------------------------------------------
    def _call(self, handler: Callable[..., Any], *args: Any) -> None:
        with self._lock:
            loop = self._loop
        if loop is None or loop.is_closed():
            self.dropped += 1
            return
        try:
            loop.call_soon_threadsafe(handler, *args)
        except RuntimeError:  # the loop closed meanwhile
            self.dropped += 1

    def submit_event(self, robot: str, event: Dict[str, Any]) -> None:
        """A status, activity, transition, log or feedback event (:mod:`flex_nav.console.events`)."""
        self._call(self._on_event, robot, event)

    def submit_structure(self, robot: str, text: str) -> None:
        """A runner's ``~structure`` JSON text."""
        self._call(self._on_structure, robot, text)

    def submit_userdata(self, robot: str, text: str) -> None:
        """A runner's ``~userdata`` JSON text (read here, in the caller's thread)."""
        try:
            event = userdata_event(robot, text)
        except UserdataError as err:
            event = {"type": "error", "robot": robot, "message": f"unreadable userdata: {err}"}
        self._call(self._on_userdata, robot, event)

    def submit_robots(self, robots: Sequence[str]) -> None:
        """The runners found on the master now."""
        self._call(self._on_robots, list(robots))

    def submit_map(self, geometry: GridGeometry, data: Any) -> None:
        """An occupancy grid (``data`` as in nav_msgs/OccupancyGrid); its PNG is made here, in the caller's thread.
        MapViewError for a map that is not shown."""
        with self._map_lock:
            event = self.map.update(geometry, data)
        if event is not None:
            self._call(self.broadcast, event)

    def submit_overlay(self, event: Dict[str, Any]) -> None:
        """A robot's overlay event (:mod:`flex_nav.console.mapview`)."""
        self._call(self._on_overlay, event)

    # --- event loop --------------------------------------------------------------------------------------
    def attach_loop(self, loop: Optional[asyncio.AbstractEventLoop]) -> None:
        with self._lock:
            self._loop = loop

    def broadcast(self, event: Mapping[str, Any]) -> None:
        text = json.dumps(event, separators=(",", ":"))
        for client in list(self.clients.values()):
            client.put(text)

    def _on_robots(self, robots: List[str]) -> None:
        if set(robots) == set(self.robots):
            return  # discovery runs every few seconds: only changes are news
        for gone in set(self.robots) - set(robots):
            del self.robots[gone]
            self.tracker.forget(gone)
        for robot in robots:
            self.robots.setdefault(robot, RobotView())
        self.broadcast(robots_event(list(self.robots)))

    def _on_overlay(self, event: Dict[str, Any]) -> None:
        view = self.robots.get(event["robot"])
        if view is None:
            return
        view.overlays[event["kind"]] = event
        self.broadcast(event)

    def _on_userdata(self, robot: str, event: Dict[str, Any]) -> None:
        view = self.robots.get(robot)
        if view is None:
            return
        if event["type"] == "userdata":
            view.userdata = event
        self.broadcast(event)

    def _on_event(self, robot: str, event: Dict[str, Any]) -> None:
        view = self.robots.get(robot)
        if view is None:
            return
        kind = event.get("type")
        if kind == "status":
            view.status = event
        elif kind == "activity":
            view.activity = event
        elif kind == "feedback":
            event = {**event, "refs": self.tracker.answered(robot, event["command"], event["args"], event["pending"])}
        if kind in ("log", "transition", "feedback"):
            view.history.append(event)
        self.broadcast(event)

    def _on_structure(self, robot: str, text: str) -> None:
        view = self.robots.get(robot)
        if view is None:
            return
        try:
            structure = BehaviorStructure.from_json(text)
        except StructureError as err:
            self.broadcast({"type": "error", "robot": robot, "message": f"unreadable structure: {err}"})
            return
        view.structure, view.structure_text = structure, text  # commands are checked against it from now on
        asyncio.get_running_loop().create_task(self._draw(robot, text, structure))

    async def _draw(self, robot: str, text: str, structure: BehaviorStructure) -> None:
        svg, error = await self.svg(text, structure, ())
        view = self.robots.get(robot)
        if view is None or view.structure_text != text:  # gone, or a newer structure came meanwhile
            return
        view.structure_event = structure_event(robot, structure, svg, error)
        self.broadcast(view.structure_event)

    async def svg(self, text: str, structure: BehaviorStructure, folded: Sequence[str]) -> Tuple[str, str]:
        """(SVG, "") of ``structure`` with ``folded`` containers, or ("", why not); laid out off the loop, cached."""
        key = (structure.behavior, text, tuple(sorted(folded)))
        cached = self._svg_cache.get(key)
        if cached is None:
            try:
                cached = (await asyncio.to_thread(self.render, structure, key[2]), "")
            except FlexNavError as err:
                cached = ("", str(err))
            if len(self._svg_cache) >= 32:
                self._svg_cache.pop(next(iter(self._svg_cache)))
            self._svg_cache[key] = cached
        return cached

    def snapshot(self) -> List[Dict[str, Any]]:
        """Everything a page needs when it connects (or falls behind): robots, then each one's state."""
        events: List[Dict[str, Any]] = [robots_event(list(self.robots))]
        with self._map_lock:
            whole_map = self.map.whole_event()  # encoded here only if patches came since it was last sent whole
        if whole_map is not None:
            events.append(whole_map)
        for view in self.robots.values():
            events.extend(e for e in (view.structure_event, view.status, view.activity, view.userdata)
                          if e is not None)
            events.extend(view.overlays.values())
            events.extend(view.history)
        return events

    # --- commands from a page ------------------------------------------------------------------------------
    def command(self, client: int, data: Mapping[str, Any]) -> Dict[str, Any]:
        """Validate and send one command; the answer for the page (sent, or refused with the reason)."""
        ref = f"{client}:{known_ref(data.get('id'))}"
        robot = data.get("robot")
        try:
            if not isinstance(robot, str) or robot not in self.robots:
                raise refuse_choice("robot", "robot", robot, sorted(self.robots))
            view = self.robots[robot]
            command = validate_command(data, view.structure, view.active())
            self.send(robot, command)
        except CommandRefused as err:
            return {"type": "refused", "ref": ref, "robot": robot, "reason": str(err), "field": err.field}
        except FlexNavError as err:
            return {"type": "refused", "ref": ref, "robot": robot, "reason": str(err), "field": ""}
        self.tracker.sent(robot, command.command, command.args, ref)
        return {"type": "sent", "ref": ref, "robot": robot, "command": command.command, "args": list(command.args)}

    async def message(self, client: int, text: str) -> Dict[str, Any]:
        """A page's message: a command, a request for the graph with some containers folded, a goal, or a request
        to forget the remembered obstacles."""
        try:
            data = json.loads(text, parse_constant=_no_constant)
        except (ValueError, RecursionError) as err:
            return {"type": "error", "message": f"not a JSON message: {err}"}
        if not isinstance(data, dict):
            return {"type": "error", "message": "a message must be a JSON object"}
        kind = data.get("type")
        if kind == "fold":
            return await self.fold(data)
        handlers = {"command": self.command, "goal": self.goal, "forget_memory": self.forget}
        handler = handlers.get(kind) if isinstance(kind, str) else None
        if handler is None:
            return {"type": "error", "message": str(refuse_choice("message type", "type", kind, list(MESSAGE_TYPES)))}
        return handler(client, data)

    def forget(self, client: int, data: Mapping[str, Any]) -> Dict[str, Any]:
        """Start asking a robot's global costmap to forget its remembered obstacles; ``forget_pending`` (the
        costmap's answer follows as ``memory_forgotten``) or ``refused``."""
        ref = f"{client}:{known_ref(data.get('id'))}"
        robot = data.get("robot")
        if not isinstance(robot, str) or robot not in self.robots:
            err = refuse_choice("robot", "robot", robot, sorted(self.robots))
            return {"type": "refused", "ref": ref, "robot": robot, "reason": str(err), "field": err.field}
        if robot in self._forgetting:
            return {"type": "refused", "ref": ref, "robot": robot, "field": "",
                    "reason": f"{robot} was asked to forget its remembered obstacles already; wait for its answer"}
        self._forgetting.add(robot)
        task = asyncio.get_running_loop().create_task(self._forget(client, ref, robot))
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)
        return {"type": "forget_pending", "ref": ref, "robot": robot}

    async def _forget(self, client: int, ref: str, robot: str) -> None:
        loop = asyncio.get_running_loop()

        def ask() -> Tuple[bool, str]:
            try:
                return self.forget_memory(robot)
            finally:  # only now may the robot be asked again (a call that timed out still holds its thread)
                with contextlib.suppress(RuntimeError):  # the loop closed meanwhile
                    loop.call_soon_threadsafe(self._forgetting.discard, robot)

        try:
            ok, message = await asyncio.wait_for(asyncio.to_thread(ask), FORGET_TIMEOUT_S)
        except asyncio.TimeoutError:
            ok, message = False, f"{robot} did not answer within {FORGET_TIMEOUT_S:g} s"
        except FlexNavError as err:
            ok, message = False, str(err)
        page = self.clients.get(client)
        if page is not None:
            page.put(json.dumps({"type": "memory_forgotten", "ref": ref, "robot": robot, "ok": bool(ok),
                                 "message": str(message)}, separators=(",", ":")))

    def goal(self, client: int, data: Mapping[str, Any]) -> Dict[str, Any]:
        """Check and send a goal or initial pose placed on the map; the answer for the page."""
        ref = f"{client}:{known_ref(data.get('id'))}"
        with self._map_lock:
            geometry = self.map.geometry
        try:
            request = check_goal(data, list(self.robots), geometry)
            self.send_goal(request)
        except CommandRefused as err:
            return {"type": "refused", "ref": ref, "robot": data.get("robot"), "reason": str(err), "field": err.field}
        except FlexNavError as err:
            return {"type": "refused", "ref": ref, "robot": data.get("robot"), "reason": str(err), "field": ""}
        return {"type": "goal_sent", "ref": ref, "robot": request.robot, "kind": request.kind,
                "x": request.x, "y": request.y, "yaw": request.yaw}

    async def fold(self, data: Mapping[str, Any]) -> Dict[str, Any]:
        robot, folded = data.get("robot"), data.get("folded")
        view = self.robots.get(robot) if isinstance(robot, str) else None
        if view is None or view.structure_event is None:
            return {"type": "error", "message": f"no drawing of robot {robot!r} to fold"}
        if not isinstance(folded, list) or not all(isinstance(p, str) and p in view.structure.states for p in folded):
            return {"type": "error", "message": "folded must be a list of container paths of the loaded behavior"}
        svg, error = await self.svg(view.structure_text, view.structure, folded)
        return {"type": "svg", "robot": robot, "behavior": view.structure.behavior, "folded": folded, "svg": svg,
                "error": error}

    # --- HTTP ------------------------------------------------------------------------------------------------
    def authorized(self, request: web.Request) -> bool:
        token = self.config.token
        if not token:
            return is_loopback(_host_name(request.host))
        given = request.cookies.get(COOKIE, "")
        header = request.headers.get("Authorization", "")
        if header.startswith("Bearer "):
            given = header[len("Bearer "):]
        return token_matches(given, token)

    def app(self) -> web.Application:
        app = web.Application(middlewares=[self._guard], client_max_size=self.config.max_message_bytes)
        for path in self._pages:
            app.router.add_get(path, self._page)
        app.router.add_get("/ws", self._websocket)
        app.on_startup.append(self._started)
        app.on_cleanup.append(self._stopped)
        return app

    async def _started(self, app: web.Application) -> None:
        self.attach_loop(asyncio.get_running_loop())

    async def _stopped(self, app: web.Application) -> None:
        self.attach_loop(None)

    @web.middleware
    async def _guard(self, request: web.Request,
                     handler: Callable[[web.Request], Awaitable[web.StreamResponse]]) -> web.StreamResponse:
        offered = request.query.get("token")
        if offered is not None and self.config.token and request.path == "/":
            if not token_matches(offered, self.config.token):
                return _refusal(401, "wrong token")
            redirect = web.HTTPSeeOther("/", headers=SECURITY_HEADERS)  # the token leaves the address bar at once
            redirect.set_cookie(COOKIE, offered, httponly=True, samesite="Strict", path="/")
            raise redirect
        if not self.authorized(request):
            if self.config.token:
                return _refusal(401, "a token is needed: open /?token=... once")
            return _refusal(403, "this console answers only to loopback host names")
        response = await handler(request)
        response.headers.update(SECURITY_HEADERS)
        return response

    async def _page(self, request: web.Request) -> web.Response:
        body, kind = self._pages[request.path]
        return web.Response(body=body, content_type=kind, charset="utf-8")

    async def _websocket(self, request: web.Request) -> web.StreamResponse:
        origin = request.headers.get("Origin", "")
        expected = f"{request.scheme}://{request.host}"
        if not hmac.compare_digest(origin.encode("utf-8", "replace"), expected.encode("utf-8", "replace")):
            return _refusal(403, f"websocket from origin {origin[:100]!r} refused (only the console's own page)")
        if len(self.clients) >= self.config.max_clients:
            return _refusal(503, f"{self.config.max_clients} pages are connected already")
        ws = web.WebSocketResponse(max_msg_size=self.config.max_message_bytes, heartbeat=20.0)
        await ws.prepare(request)
        client = _Client(next(self._numbers), self.config.client_queue)
        client.put(json.dumps({"type": "hello", "client": client.number}))
        client.queue.put_nowait(None)  # then the snapshot, then what happens
        self.clients[client.number] = client
        writer = asyncio.get_running_loop().create_task(self._write(ws, client))
        try:
            async for msg in ws:
                if msg.type != WSMsgType.TEXT:
                    continue
                answer = await self.message(client.number, msg.data)
                client.put(json.dumps(answer, separators=(",", ":")))
        finally:
            del self.clients[client.number]
            writer.cancel()
        return ws

    async def _write(self, ws: web.WebSocketResponse, client: _Client) -> None:
        while not ws.closed:
            item = await client.queue.get()
            if item is None:
                await ws.send_str(json.dumps({"type": "snapshot"}))  # the page drops its history: it comes again
                for event in self.snapshot():
                    await ws.send_str(json.dumps(event, separators=(",", ":")))
                await ws.send_str(json.dumps({"type": "snapshot_done", "resyncs": client.resyncs}))
            else:
                await ws.send_str(item)


def _no_goals(request: GoalRequest) -> None:
    raise NotReadyError("this console sends no goals")


def _no_memory(robot: str) -> Tuple[bool, str]:
    raise NotReadyError("this console reaches no obstacle memory")


def _no_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a JSON number")


def _host_name(host: str) -> str:
    """The name of a ``Host`` header without its port (``[::1]:8080`` -> ``::1``)."""
    if host.startswith("["):
        return host[1:].split("]", 1)[0]
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def _refusal(status: int, reason: str) -> web.Response:
    return web.Response(status=status, text=reason + "\n", headers=SECURITY_HEADERS)


async def serve(console: Console, stop: asyncio.Event, ready: Callable[[], None] = lambda: None) -> None:
    """Serve until ``stop`` is set, calling ``ready()`` once listening; ConfigError (with the reason) when the
    address cannot be bound."""
    runner = web.AppRunner(console.app(), access_log=None)
    await runner.setup()
    try:
        site = web.TCPSite(runner, console.config.host, console.config.port)
        try:
            await site.start()
        except OSError as err:
            raise ConfigError(f"cannot serve on {console.config.host}:{console.config.port}: {err}") from err
        ready()
        await stop.wait()
    finally:
        await runner.cleanup()
