"""The console's aiohttp app driven by aiohttp's test client (no ROS, no browser): the page and its headers, the
token on every request (compared in constant time), the websocket's origin check, the bounds, and a command's
round trip from the page into a recording publisher and the runner's answer back to the page."""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import json
import threading
import time
from typing import Any, AsyncIterator, Callable, Coroutine, Dict, List, Sequence, Tuple

import aiohttp
import pytest
from aiohttp.test_utils import TestClient, TestServer
from unit.console.console_testlib import structure_text

from flex_nav.console import server as server_module
from flex_nav.console.commands import RunnerCommand
from flex_nav.console.events import feedback_event
from flex_nav.console.model import BehaviorStructure
from flex_nav.console.server import COOKIE, Console, ServerConfig, _Client
from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.msg import BehaviorCommandFeedback

ROBOT = "/robot1/behavior_runner"
TOKEN = "s3cret-token-0123456789"


class Recorder:
    """The ROS side's publisher, recorded."""

    def __init__(self) -> None:
        self.sent: List[Tuple[str, RunnerCommand]] = []

    def __call__(self, robot: str, command: RunnerCommand) -> None:
        if robot == "/silent/behavior_runner":
            raise NotReadyError(f"the runner {robot} does not listen on {robot}/command (yet); try again")
        self.sent.append((robot, command))


def fake_render(structure: BehaviorStructure, folded: Sequence[str]) -> str:
    return f'<svg id="drawn" data-behavior="{structure.behavior}" data-folded="{",".join(folded)}"/>'


def run(coroutine: Coroutine[Any, Any, Any]) -> Any:
    return asyncio.run(asyncio.wait_for(coroutine, 30.0))


@contextlib.asynccontextmanager
async def served(console: Console) -> AsyncIterator[TestClient]:
    client = TestClient(TestServer(console.app(), host="127.0.0.1"))
    await client.start_server()
    try:
        yield client
    finally:
        await client.close()


def origin(client: TestClient) -> str:
    return f"http://{client.host}:{client.port}"


async def until(ws: aiohttp.ClientWebSocketResponse, wanted: Callable[[Dict[str, Any]], bool],
                seen: List[Dict[str, Any]] | None = None) -> Dict[str, Any]:
    while True:
        msg = await asyncio.wait_for(ws.receive(), 5.0)
        assert msg.type == aiohttp.WSMsgType.TEXT, msg
        event: Dict[str, Any] = json.loads(msg.data)
        if seen is not None:
            seen.append(event)
        if wanted(event):
            return event


def console(**config: Any) -> Tuple[Console, Recorder]:
    recorder = Recorder()
    return Console(ServerConfig(**config), recorder, fake_render), recorder


async def page(client: TestClient) -> aiohttp.ClientWebSocketResponse:
    """A page's websocket, its hello and snapshot read."""
    ws = await client.ws_connect("/ws", headers={"Origin": origin(client)})
    await until(ws, lambda e: e["type"] == "snapshot_done")
    return ws


async def runner_says(made: Console, ws: aiohttp.ClientWebSocketResponse, robots: Sequence[str],
                      active: Sequence[str] = ()) -> None:
    """The ROS side (from its own threads) reports ``robots``, flex_planner loaded on ROBOT and ``active`` states
    there (none: no activity); returns once the page has seen them."""
    await asyncio.to_thread(made.submit_robots, list(robots))
    await asyncio.to_thread(made.submit_structure, ROBOT, structure_text("flex_planner"))
    await until(ws, lambda e: e["type"] == "structure")
    if active:
        await asyncio.to_thread(made.submit_event, ROBOT, {
            "type": "activity", "robot": ROBOT, "behavior": "flex_planner", "autonomy": 1, "active": list(active),
            "requests": [], "stamp": 1.0})
        await until(ws, lambda e: e["type"] == "activity")


# --- configuration -------------------------------------------------------------------------------------------
def test_any_host_but_loopback_needs_a_long_token() -> None:
    with pytest.raises(ConfigError, match=r"host '0\.0\.0\.0' is reachable from other machines: set a token"):
        ServerConfig(host="0.0.0.0")
    with pytest.raises(ConfigError, match="the token has 5 characters; use at least 16"):
        ServerConfig(host="10.0.0.1", token="short")
    with pytest.raises(ConfigError, match="port 70000 is not a TCP port"):
        ServerConfig(port=70000)
    for host in ("127.0.0.1", "localhost", "::1", "127.0.0.2"):
        assert ServerConfig(host=host).token == ""
    assert ServerConfig(host="192.168.1.5", token=TOKEN).host == "192.168.1.5"


# --- HTTP --------------------------------------------------------------------------------------------------------
def test_the_page_and_its_files_are_served_with_strict_headers() -> None:
    async def check() -> None:
        made, _ = console(port=0)
        async with served(made) as client:
            page = await client.get("/")
            assert page.status == 200 and page.content_type == "text/html"
            assert "flex_nav console" in await page.text()
            assert "script-src 'self'" in page.headers["Content-Security-Policy"]
            assert page.headers["X-Frame-Options"] == "DENY"
            script = await client.get("/console.js")
            assert script.content_type == "text/javascript" and "new WebSocket" in await script.text()
            assert (await client.get("/console.css")).status == 200
            assert (await client.get("/../server.py")).status == 404
            assert (await client.get("/web/index.html")).status == 404
            assert (await client.post("/", data="x")).status == 405
    run(check())


def test_without_a_token_only_loopback_host_names_are_served() -> None:
    async def check() -> None:
        made, _ = console(port=0)
        async with served(made) as client:
            assert (await client.get("/", headers={"Host": f"localhost:{client.port}"})).status == 200
            rebound = await client.get("/", headers={"Host": f"evil.example:{client.port}"})
            assert rebound.status == 403 and "loopback" in await rebound.text()
    run(check())


def test_with_a_token_every_request_needs_it(monkeypatch: pytest.MonkeyPatch) -> None:
    compared: List[Tuple[bytes, bytes]] = []
    real = hmac.compare_digest

    def spy(a: bytes, b: bytes) -> bool:
        compared.append((a, b))
        return real(a, b)

    monkeypatch.setattr(server_module.hmac, "compare_digest", spy)

    async def check() -> None:
        made, _ = console(port=0, token=TOKEN)
        async with served(made) as client:
            for path in ("/", "/console.js", "/ws"):
                assert (await client.get(path)).status == 401
            wrong = {"Cookie": f"{COOKIE}=not-the-token-at-all"}
            assert (await client.get("/", headers=wrong)).status == 401
            assert (await client.get("/", headers={"Authorization": "Bearer nope"})).status == 401
            assert (await client.get(f"/?token={TOKEN}x", allow_redirects=False)).status == 401
            compared.clear()
            opened = await client.get(f"/?token={TOKEN}", allow_redirects=False)
            assert opened.status == 303 and opened.headers["Location"] == "/"
            cookie = opened.headers["Set-Cookie"]
            assert f"{COOKIE}={TOKEN}" in cookie and "HttpOnly" in cookie and "SameSite=Strict" in cookie
            assert compared == [(TOKEN.encode(), TOKEN.encode())]  # the one comparison: constant time
            good = {"Cookie": f"{COOKIE}={TOKEN}"}
            assert (await client.get("/", headers=good)).status == 200
            assert (await client.get("/console.js", headers={"Authorization": f"Bearer {TOKEN}"})).status == 200
    run(check())


# --- websocket -------------------------------------------------------------------------------------------------
def test_the_websocket_checks_the_token_and_the_origin() -> None:
    async def check() -> None:
        made, _ = console(port=0, token=TOKEN)
        async with served(made) as client:
            good = {"Cookie": f"{COOKIE}={TOKEN}", "Origin": origin(client)}
            for headers, status in (({"Origin": origin(client)}, 401),  # no token
                                    ({"Cookie": f"{COOKIE}={TOKEN}"}, 403),  # no origin
                                    ({**good, "Origin": "http://evil.example"}, 403),
                                    ({**good, "Origin": f"https://{client.host}:{client.port}"}, 403)):
                with pytest.raises(aiohttp.WSServerHandshakeError) as refused:
                    await client.ws_connect("/ws", headers=headers)
                assert refused.value.status == status, headers
            ws = await client.ws_connect("/ws", headers=good)
            hello = await until(ws, lambda e: True)
            assert hello == {"type": "hello", "client": 1}
            await ws.close()
    run(check())


def test_a_command_round_trip_from_the_page_to_the_runner_and_back() -> None:
    async def check() -> None:
        made, recorder = console(port=0)
        async with served(made) as client:
            ws = await page(client)
            await runner_says(made, ws, [ROBOT], active=["/ApprovePlan"])
            drawn = made.robots[ROBOT].structure_event
            assert drawn is not None and 'data-behavior="flex_planner"' in drawn["svg"]
            await ws.send_json({"type": "command", "id": 7, "robot": ROBOT, "command": "force",
                                "path": "/ApprovePlan", "outcome": "execute"})
            sent = await until(ws, lambda e: e["type"] in ("sent", "refused"))
            assert sent == {"type": "sent", "ref": "1:7", "robot": ROBOT, "command": "force",
                            "args": ["/ApprovePlan", "execute"]}
            assert recorder.sent == [(ROBOT, RunnerCommand("force", ("/ApprovePlan", "execute")))]
            answer = BehaviorCommandFeedback(command="force", args=["/ApprovePlan", "execute"], ok=True,
                                             message="forced /ApprovePlan -> execute", pending=False)
            await asyncio.to_thread(made.submit_event, ROBOT, feedback_event(ROBOT, answer))
            back = await until(ws, lambda e: e["type"] == "feedback")
            assert back["refs"] == ["1:7"] and back["ok"] and back["message"] == "forced /ApprovePlan -> execute"
            await ws.close()
    run(check())


def test_commands_are_refused_with_the_reason_and_never_sent() -> None:
    async def check() -> None:
        made, recorder = console(port=0)
        async with served(made) as client:
            ws = await page(client)
            await runner_says(made, ws, [ROBOT, "/silent/behavior_runner"], active=["/ReceiveGoal"])
            cases: List[Tuple[Dict[str, Any], str, str]] = [
                ({"robot": "/robot9/behavior_runner", "command": "pause"},
                 "robot '/robot9/behavior_runner' is not valid (valid: /robot1/behavior_runner, "
                 "/silent/behavior_runner)", "robot"),
                ({"robot": ROBOT, "command": "force", "path": "/ApprovePlan", "outcome": "go"},
                 "force: outcome of /ApprovePlan 'go' is not valid (valid: execute, replan, abort)", "outcome"),
                ({"robot": ROBOT, "command": "force", "path": "/ApprovePlan", "outcome": "execute"},
                 "force: state '/ApprovePlan' is not active (active: /ReceiveGoal)", "path"),
                ({"robot": ROBOT, "command": "start", "behavior": "flex_planner", "parameters": {"max_replans": -1}},
                 "parameter 'max_replans' = -1.0 is below its minimum 0.0", "parameters.max_replans"),
                ({"robot": "/silent/behavior_runner", "command": "pause"},
                 "the runner /silent/behavior_runner does not listen on /silent/behavior_runner/command (yet); "
                 "try again", ""),
            ]
            for index, (fields, reason, field) in enumerate(cases):
                await ws.send_json({"type": "command", "id": index, **fields})
                answer = await until(ws, lambda e: e["type"] in ("sent", "refused"))
                assert answer == {"type": "refused", "ref": f"1:{index}", "robot": fields["robot"],
                                  "reason": reason, "field": field}
            assert recorder.sent == []
            await ws.send_str('{"type": "command", "robot": "x", "command": "autonomy", "level": NaN}')
            assert "NaN is not a JSON number" in (await until(ws, lambda e: e["type"] == "error"))["message"]
            await ws.send_str("eval('1')")
            assert "not a JSON message" in (await until(ws, lambda e: e["type"] == "error"))["message"]
            await ws.send_json({"type": "exec"})
            assert "message type 'exec' is not valid (valid: command, fold, goal, forget_memory)" in (
                await until(ws, lambda e: e["type"] == "error"))["message"]
            await ws.close()
    run(check())


def test_forget_remembered_obstacles_answers_the_page_with_the_costmaps_answer_or_why_not(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(server_module, "FORGET_TIMEOUT_S", 0.5)
    asked: List[str] = []
    release = threading.Event()

    def forget(robot: str) -> Tuple[bool, str]:
        asked.append(robot)
        if robot == "/slow/behavior_runner":
            release.wait(5.0)
            return True, "late"
        if robot == "/off/behavior_runner":
            raise NotReadyError("no service /off/get_path_server/global_costmap/clear_obstacle_memory (within 2 s): "
                                "is the obstacle memory of get_path_server/global_costmap off?")
        return True, "2 remembered obstacle(s) forgotten"

    async def check() -> None:
        made, recorder = console(port=0)
        made.forget_memory = forget
        async with served(made) as client:
            ws = await page(client)
            await runner_says(made, ws, [ROBOT, "/off/behavior_runner", "/slow/behavior_runner"])
            await ws.send_json({"type": "forget_memory", "id": 1, "robot": ROBOT})
            assert await until(ws, lambda e: e["type"] == "forget_pending") == {
                "type": "forget_pending", "ref": "1:1", "robot": ROBOT}
            assert await until(ws, lambda e: e["type"] == "memory_forgotten") == {
                "type": "memory_forgotten", "ref": "1:1", "robot": ROBOT, "ok": True,
                "message": "2 remembered obstacle(s) forgotten"}
            await ws.send_json({"type": "forget_memory", "id": 2, "robot": "/off/behavior_runner"})
            off = await until(ws, lambda e: e["type"] == "memory_forgotten")
            assert off["ref"] == "1:2" and off["ok"] is False and off["message"].startswith("no service /off/")
            await ws.send_json({"type": "forget_memory", "id": 3, "robot": "/robot9/behavior_runner"})
            refused = await until(ws, lambda e: e["type"] in ("forget_pending", "refused"))
            assert refused["type"] == "refused" and refused["field"] == "robot"
            assert "robot '/robot9/behavior_runner' is not valid" in refused["reason"]
            await ws.send_json({"type": "forget_memory", "id": 4, "robot": "/slow/behavior_runner"})
            await until(ws, lambda e: e["type"] == "forget_pending")
            await ws.send_json({"type": "forget_memory", "id": 5, "robot": "/slow/behavior_runner"})
            twice = await until(ws, lambda e: e["type"] in ("forget_pending", "refused", "memory_forgotten"))
            assert twice["type"] == "refused" and "wait for its answer" in twice["reason"], twice
            late = await until(ws, lambda e: e["type"] == "memory_forgotten")
            assert late["ref"] == "1:4" and late["ok"] is False and "did not answer within 0.5 s" in late["message"]
            await ws.send_json({"type": "forget_memory", "id": 6, "robot": "/slow/behavior_runner"})
            still = await until(ws, lambda e: e["type"] in ("forget_pending", "refused"))
            assert still["type"] == "refused", "a robot whose call still hangs was asked again"
            release.set()  # the hanging call ends: the robot may be asked again
            for _ in range(50):
                await ws.send_json({"type": "forget_memory", "id": 7, "robot": "/slow/behavior_runner"})
                again = await until(ws, lambda e: e["type"] in ("forget_pending", "refused"))
                if again["type"] == "forget_pending":
                    break
                await asyncio.sleep(0.05)
            assert again["type"] == "forget_pending", again
            assert (await until(ws, lambda e: e["type"] == "memory_forgotten"))["message"] == "late"
            assert asked == [ROBOT, "/off/behavior_runner", "/slow/behavior_runner", "/slow/behavior_runner"]
            assert recorder.sent == []  # nothing went to the runners' command topics
            await ws.close()
    run(check())


def test_a_new_page_gets_a_snapshot_and_can_fold_containers() -> None:
    async def check() -> None:
        made, _ = console(port=0)
        async with served(made) as client:
            first = await page(client)
            await runner_says(made, first, [ROBOT])
            await asyncio.to_thread(made.submit_event, ROBOT, {"type": "log", "robot": ROBOT, "behavior": "b",
                                                               "level": "INFO", "path": "/", "text": "hi",
                                                               "stamp": 1.0})
            await until(first, lambda e: e["type"] == "log")
            second = await client.ws_connect("/ws", headers={"Origin": origin(client)})
            seen: List[Dict[str, Any]] = []
            await until(second, lambda e: e["type"] == "snapshot_done", seen)
            assert [e["type"] for e in seen] == ["hello", "snapshot", "robots", "structure", "log", "snapshot_done"]
            assert seen[0]["client"] == 2 and seen[2]["robots"] == [ROBOT]
            await second.send_json({"type": "fold", "robot": ROBOT, "folded": ["/Navigate"]})
            folded = await until(second, lambda e: e["type"] == "svg")
            assert folded["folded"] == ["/Navigate"] and 'data-folded="/Navigate"' in folded["svg"]
            await second.send_json({"type": "fold", "robot": ROBOT, "folded": ["/Nowhere"]})
            assert "container paths" in (await until(second, lambda e: e["type"] == "error"))["message"]
            await first.close()
            await second.close()
    run(check())


def test_runners_that_go_away_are_dropped_and_unreadable_structures_reported() -> None:
    async def check() -> None:
        made, _ = console(port=0)
        async with served(made) as client:
            ws = await page(client)
            await asyncio.to_thread(made.submit_robots, [ROBOT])
            assert (await until(ws, lambda e: e["type"] == "robots"))["robots"] == [ROBOT]
            await asyncio.to_thread(made.submit_robots, [ROBOT])  # discovery again, nothing new: no event
            await asyncio.to_thread(made.submit_structure, ROBOT, '{"schema": "flex_nav/behavior_structure"}')
            error = await until(ws, lambda e: True)  # the very next event
            assert error["type"] == "error"
            assert error["robot"] == ROBOT and "unreadable structure: structure has no 'version'" in error["message"]
            await asyncio.to_thread(made.submit_robots, [])
            assert (await until(ws, lambda e: e["type"] == "robots"))["robots"] == []
            assert made.robots == {}
            await ws.close()
    run(check())


def test_commands_are_checked_against_a_new_structure_before_it_is_drawn() -> None:
    def slow_render(structure: BehaviorStructure, folded: Sequence[str]) -> str:
        if structure.behavior == "explore":
            time.sleep(0.5)  # a big layout: the command below arrives while it is drawn
        return fake_render(structure, folded)

    async def check() -> None:
        recorder = Recorder()
        made = Console(ServerConfig(port=0), recorder, slow_render)
        async with served(made) as client:
            ws = await page(client)
            await runner_says(made, ws, [ROBOT])
            await asyncio.to_thread(made.submit_structure, ROBOT, structure_text("explore"))
            await ws.send_json({"type": "command", "id": 1, "robot": ROBOT, "command": "lock",
                                "path": "/GoToFrontier"})  # explore's, not flex_planner's
            seen: List[Dict[str, Any]] = []
            answer = await until(ws, lambda e: e["type"] in ("sent", "refused"), seen)
            assert answer["type"] == "sent" and recorder.sent == [(ROBOT, RunnerCommand("lock", ("/GoToFrontier",)))]
            if not any(e["type"] == "structure" for e in seen):  # drawn off the loop: before or after the answer
                await until(ws, lambda e: e["type"] == "structure", seen)
            assert [e["behavior"] for e in seen if e["type"] == "structure"] == ["explore"]
            await ws.close()
    run(check())


def test_pages_and_messages_are_bounded() -> None:
    async def check() -> None:
        made, _ = console(port=0, max_clients=1, max_message_bytes=1024)
        async with served(made) as client:
            ws = await page(client)
            with pytest.raises(aiohttp.WSServerHandshakeError) as full:
                await client.ws_connect("/ws", headers={"Origin": origin(client)})
            assert full.value.status == 503
            await ws.send_str(json.dumps({"type": "fold", "robot": "x" * 2000}))
            closed = await asyncio.wait_for(ws.receive(), 5.0)
            assert closed.type in (aiohttp.WSMsgType.CLOSE, aiohttp.WSMsgType.CLOSED)
            assert ws.close_code == aiohttp.WSCloseCode.MESSAGE_TOO_BIG
    run(check())


def test_a_page_that_falls_behind_gets_a_snapshot_instead_of_the_backlog() -> None:
    async def check() -> None:
        slow = _Client(1, queue_size=3)
        for index in range(5):
            slow.put(str(index))
        assert slow.resyncs == 1 and slow.queue.qsize() <= 3
        items = [slow.queue.get_nowait() for _ in range(slow.queue.qsize())]
        assert None in items  # the marker: the writer sends a fresh snapshot there
        assert "0" not in items  # the oldest backlog is gone
    run(check())


def test_events_before_the_server_runs_are_counted_not_queued() -> None:
    made, _ = console(port=0)
    made.submit_robots([ROBOT])
    made.submit_event(ROBOT, {"type": "log"})
    assert made.dropped == 2 and made.robots == {}
