"""The console node's ROS side without a master: it refuses to start without a token off loopback (exit 2, the
reason, the token never echoed), and finds runners through a bounded XML-RPC call to the master."""

from __future__ import annotations

import threading
import xmlrpc.server
from typing import Any, ClassVar, Dict, Iterator, List, Tuple

import pytest
import rospy

from flex_nav.console.commands import RunnerCommand
from flex_nav.console.server import Console, ServerConfig
from flex_nav.exceptions import NotReadyError
from flex_nav.nodes import console as node


def start_with(monkeypatch: pytest.MonkeyPatch, private: Dict[str, Any]) -> int:
    def get_param(name: str, default: Any = None) -> Any:
        if name == "~":
            return dict(private)
        return private.get(name.lstrip("~"), default)

    monkeypatch.setattr(node, "init_node", lambda name: None)
    monkeypatch.setattr(rospy, "get_param", get_param)
    monkeypatch.setattr(node.asyncio, "run", lambda coroutine: coroutine.close())  # never serve in a test
    return int(node.main())


def test_a_host_off_loopback_without_a_token_exits_2_with_the_reason(monkeypatch: pytest.MonkeyPatch,
                                                                      capsys: pytest.CaptureFixture[str]) -> None:
    assert start_with(monkeypatch, {"host": "0.0.0.0"}) == 2
    assert "host '0.0.0.0' is reachable from other machines: set a token" in capsys.readouterr().err


def test_bad_tokens_and_unknown_parameters_exit_2_without_echoing_the_token(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    assert start_with(monkeypatch, {"host": "10.1.2.3", "token": 1234567890123456789}) == 2
    err = capsys.readouterr().err
    assert "~token must be a string" in err and "1234567890123456789" not in err
    assert start_with(monkeypatch, {"host": "10.1.2.3", "token": "tiny-secret"}) == 2
    err = capsys.readouterr().err
    assert "the token has 11 characters" in err and "tiny-secret" not in err
    assert start_with(monkeypatch, {"prot": 8081}) == 2
    assert ("prot is not a parameter of this node (valid: discovery_period_s, goal_topic, host, map_topic, "
            "max_clients, memory_costmap, port, pose_period_s, token)") in capsys.readouterr().err


def test_a_good_configuration_serves(monkeypatch: pytest.MonkeyPatch) -> None:
    assert start_with(monkeypatch, {"host": "10.1.2.3", "token": "a-long-enough-token-1234", "port": 8099}) == 0


@pytest.fixture
def master() -> Iterator[Tuple[str, List[List[str]]]]:
    topics: List[List[str]] = []
    server = xmlrpc.server.SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
    server.register_function(lambda caller, subgraph: [1, "topics", topics], "getPublishedTopics")
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/", topics
    finally:
        server.shutdown()
        server.server_close()


class FakeLink:
    closed: ClassVar[List[str]] = []

    def __init__(self, name: str, console: Console) -> None:
        self.name = name
        console.submit_event(name, {"type": "status"})  # a latched message arrives as soon as it subscribes

    def send(self, command: RunnerCommand) -> None:
        raise AssertionError("not in this test")

    def close(self) -> None:
        FakeLink.closed.append(self.name)


def test_runners_are_discovered_and_dropped(monkeypatch: pytest.MonkeyPatch,
                                            master: Tuple[str, List[List[str]]]) -> None:
    uri, topics = master
    monkeypatch.setattr(node, "RunnerLink", FakeLink)
    monkeypatch.setattr(rospy, "get_name", lambda: "/console")
    FakeLink.closed = []
    made = Console(ServerConfig(), lambda robot, command: None)
    said: List[Tuple[str, Any]] = []
    monkeypatch.setattr(made, "submit_robots", lambda robots: said.append(("robots", list(robots))))
    monkeypatch.setattr(made, "submit_event", lambda robot, event: said.append(("event", robot)))
    registry = node.RunnerRegistry(made, uri, 1.0)
    topics.extend([["/robot1/behavior_runner/status", "flex_nav/BehaviorStatus"], ["/rosout", "rosgraph_msgs/Log"]])
    assert registry.discover_once() == ["/robot1/behavior_runner"]
    # the console knows a runner before its first (latched) message: else the message would be dropped
    assert said == [("robots", ["/robot1/behavior_runner"]), ("event", "/robot1/behavior_runner")]
    topics[:] = [["/robot2/behavior_runner/status", "flex_nav/BehaviorStatus"]]
    assert registry.discover_once() == ["/robot2/behavior_runner"]
    assert FakeLink.closed == ["/robot1/behavior_runner"] and list(registry.links) == ["/robot2/behavior_runner"]
    with pytest.raises(NotReadyError, match="no behavior runner /robot1/behavior_runner on the master"):
        registry.send("/robot1/behavior_runner", RunnerCommand("pause"))


def test_a_master_that_does_not_answer_is_not_ready() -> None:
    with pytest.raises(NotReadyError, match="did not list its topics"):
        node.published_topics("http://127.0.0.1:9/", "/console", timeout_s=0.5)
