"""``rosrun flex_nav console [_host:=127.0.0.1] [_port:=8080] [_token:=...]``: the web operator console.

Serves one page and a websocket (:mod:`flex_nav.console.server`, aiohttp) and connects them to every behavior
runner on the master: every ``discovery_period_s`` it asks the master for the topics of type
flex_nav/BehaviorStatus, so namespaced robots (``/robot1/behavior_runner``) are found as they come and go, and
subscribes each runner's ``status``, ``activity``, ``structure``, ``log``, ``transitions`` and
``command_feedback``; commands validated by the server are published on its ``command`` topic.

Parameters (private; unknown names are refused):

- ``~host`` (str, "127.0.0.1"): address to bind. Any address other than a loopback one needs ``~token``.
- ``~port`` (int, 8080): TCP port.
- ``~token`` (str, ""): required on every request when set (open ``http://HOST:PORT/?token=TOKEN`` once); at
  least 16 characters. Anyone on the ROS graph can read parameters: the token guards the web port, not ROS.
- ``~discovery_period_s`` (float, 2.0): how often the master is asked for runners [s].
- ``~max_clients`` (int, 16): pages connected at once.

A bad parameter, a missing token for a non-loopback host or a port that cannot be bound ends the node with
exit status 2 and the reason.
"""

from __future__ import annotations

import asyncio
import os
import shutil
import sys
import threading
import xmlrpc.client
from typing import Any, Callable, Dict, List, Sequence, Tuple

import rospy
from std_msgs.msg import String

from flex_nav.console.commands import RunnerCommand
from flex_nav.console.events import activity_event, feedback_event, log_event, status_event, transition_event
from flex_nav.console.graph import DOT_TIMEOUT_S
from flex_nav.console.model import runner_names
from flex_nav.console.server import Console, ServerConfig, is_loopback, serve
from flex_nav.exceptions import ConfigError, FlexNavError, NotReadyError
from flex_nav.msg import (
    BehaviorActivity,
    BehaviorCommand,
    BehaviorCommandFeedback,
    BehaviorLog,
    BehaviorStatus,
    BehaviorTransition,
)
from flex_nav.ros.master_probe import MASTER_CALL_TIMEOUT_S, _TimeoutTransport
from flex_nav.ros.node import init_node
from flex_nav.ros.params import param_float, param_int, param_str, reject_unknown

PARAMETERS = ("host", "port", "token", "discovery_period_s", "max_clients")


def published_topics(master_uri: str, caller_id: str, timeout_s: float = MASTER_CALL_TIMEOUT_S
                     ) -> List[Tuple[str, str]]:
    """The master's published ``(topic, type)`` pairs, the call bounded by ``timeout_s`` [s]; NotReadyError if the
    master does not answer."""
    proxy = xmlrpc.client.ServerProxy(master_uri, transport=_TimeoutTransport(timeout_s))
    try:
        reply: Any = proxy.getPublishedTopics(caller_id, "")
    except (OSError, xmlrpc.client.Error) as err:
        raise NotReadyError(f"the master at {master_uri} did not list its topics: {err}") from err
    if not (isinstance(reply, list) and len(reply) == 3 and reply[0] == 1 and isinstance(reply[2], list)):
        raise NotReadyError(f"the master at {master_uri} answered getPublishedTopics with {reply!r:.200}")
    return [(str(t[0]), str(t[1])) for t in reply[2] if isinstance(t, list) and len(t) == 2]


class RunnerLink:
    """The subscriptions to one runner's topics and the publisher of its commands."""

    def __init__(self, name: str, console: Console) -> None:
        self.name = name
        self.publisher = rospy.Publisher(f"{name}/command", BehaviorCommand, queue_size=10)

        def event(make: Callable[[str, Any], Dict[str, Any]]) -> Callable[[Any], None]:
            return lambda msg: console.submit_event(name, make(name, msg))

        topics: Sequence[Tuple[str, type, Callable[[Any], None], int]] = (
            ("status", BehaviorStatus, event(status_event), 10),
            ("activity", BehaviorActivity, event(activity_event), 10),
            ("transitions", BehaviorTransition, event(transition_event), 200),
            ("log", BehaviorLog, event(log_event), 200),
            ("command_feedback", BehaviorCommandFeedback, event(feedback_event), 50),
            ("structure", String, lambda msg: console.submit_structure(name, msg.data), 2),
        )
        self.subscribers = [rospy.Subscriber(f"{name}/{topic}", kind, callback, queue_size=size)
                            for topic, kind, callback, size in topics]

    def send(self, command: RunnerCommand) -> None:
        if self.publisher.get_num_connections() == 0:
            raise NotReadyError(f"the runner {self.name} does not listen on {self.name}/command (yet); try again")
        self.publisher.publish(BehaviorCommand(command=command.command, args=list(command.args)))

    def close(self) -> None:
        for sub in self.subscribers:
            sub.unregister()
        self.publisher.unregister()


class RunnerRegistry:
    """One :class:`RunnerLink` per runner on the master, kept up to date by a discovery thread."""

    def __init__(self, console: Console, master_uri: str, period_s: float) -> None:
        self.console = console
        self.master_uri = master_uri
        self.period_s = period_s
        self.links: Dict[str, RunnerLink] = {}
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="console discovery", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread.ident is not None:  # started (a port that could not be bound never starts it)
            self._thread.join(MASTER_CALL_TIMEOUT_S + 1.0)
        with self._lock:
            links, self.links = list(self.links.values()), {}
        for link in links:
            link.close()

    def _run(self) -> None:
        while not self._stop.is_set() and not rospy.is_shutdown():
            try:
                self.discover_once()
            except NotReadyError as err:
                rospy.logwarn_throttle(30.0, f"console: {err}")
            self._stop.wait(self.period_s)

    def discover_once(self) -> List[str]:
        """Ask the master once; drop the links of runners gone, tell the console, link the new ones (after the
        console knows them: their latched messages arrive as soon as they subscribe)."""
        names = runner_names(published_topics(self.master_uri, rospy.get_name()))
        with self._lock:
            gone = [self.links.pop(name) for name in list(self.links) if name not in names]
        for link in gone:
            rospy.loginfo(f"console: behavior runner {link.name} is gone")
            link.close()
        self.console.submit_robots(names)
        with self._lock:
            for name in names:
                if name not in self.links:
                    self.links[name] = RunnerLink(name, self.console)
                    rospy.loginfo(f"console: behavior runner {name} found")
        return names

    def send(self, robot: str, command: RunnerCommand) -> None:
        with self._lock:
            link = self.links.get(robot)
        if link is None:
            raise NotReadyError(f"no behavior runner {robot} on the master")
        link.send(command)


def _not_ready(robot: str, command: RunnerCommand) -> None:
    raise NotReadyError("the console is still starting")


def read_config() -> ServerConfig:
    """The private parameters as a checked ServerConfig (ConfigError with the reason; the token never echoed)."""
    reject_unknown("~", PARAMETERS)
    token = rospy.get_param("~token", "")
    if not isinstance(token, str):
        raise ConfigError("parameter ~token must be a string (a token of digits only: quote it, "
                          "_token:=\"'0123...'\")")
    return ServerConfig(host=param_str("~host", "127.0.0.1"), port=param_int("~port", 8080, 1, 65535),
                        token=token, max_clients=param_int("~max_clients", 16, 1, 1000))


async def _serve(console: Console, registry: RunnerRegistry) -> None:
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()

    def on_shutdown() -> None:
        if not loop.is_closed():
            loop.call_soon_threadsafe(stop.set)

    rospy.on_shutdown(on_shutdown)
    config = console.config

    def ready() -> None:
        shown = f"[{config.host}]" if ":" in config.host else config.host
        url = f"http://{shown}:{config.port}/"
        how = f"open {url}?token=<your token> once" if config.token else f"open {url}"
        where = "" if is_loopback(config.host) else " (reachable from the network: the token guards it)"
        rospy.loginfo(f"console: serving on {url}{where}; {how}")
        print(f"[console] {how}", flush=True)
        registry.start()

    await serve(console, stop, ready)


def main() -> int:
    init_node("console")
    try:
        config = read_config()
        period_s = param_float("~discovery_period_s", 2.0, 0.1, 3600.0)
    except ConfigError as err:
        rospy.logfatal(f"console: {err}")
        print(f"[console] configuration error: {err}", file=sys.stderr)
        return 2
    console = Console(config, send=_not_ready)
    registry = RunnerRegistry(console, os.environ.get("ROS_MASTER_URI", ""), period_s)
    console.send = registry.send
    if shutil.which("dot") is None:
        rospy.logwarn(f"console: Graphviz's dot is not installed: behaviors will not be drawn (commands still work; "
                      f"install the Debian package graphviz; layouts are bounded by {DOT_TIMEOUT_S:g} s)")
    try:
        asyncio.run(_serve(console, registry))
    except FlexNavError as err:
        rospy.logfatal(f"console: {err}")
        print(f"[console] {err}", file=sys.stderr)
        return 2
    finally:
        registry.stop()
    return 0
