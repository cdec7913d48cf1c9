"""The connections of the FlexBE proxies: ONE process-wide set, as in FlexBE.

FlexBE keeps its proxies' publishers, subscribers and clients in class-level dicts: every ``ProxyPublisher()``,
``ProxySubscriberCached()``, ... of a process shares them, whether it was created by a state, a behavior or a test,
inside a running behavior or outside any. The compatibility layer keeps that on purpose, so FlexBE code runs as
written (a proxy created in ``__init__`` works in ``execute``, a state executed directly by flexbe_testing's Tester
reaches ROS, ``_sub._callback(msg, topic)`` injects a message for every state that reads the topic). This is the
compat layer's FlexBE semantics only: flex_nav's own states use the connections of their behavior
(``self.context.proxies``), one set per behavior, closed when it ends.

The process-wide set is a :class:`flex_nav.behavior.proxies.Proxies`: a :class:`flex_nav.ros.proxies.RosProxies`
made on first use (the process is a ROS node: ``behavior_runner``, a rostest, FlexBE's Tester), or whatever
:func:`use_process_proxies` installed (pure tests install a fake). :func:`reset_process_proxies` forgets it and every
proxy's cached state (FlexBE's ``shutdown``).
"""

from __future__ import annotations

import threading
from typing import Callable, List, Optional

from flex_nav.behavior.proxies import Proxies

_LOCK = threading.Lock()
_PROCESS: List[Optional[Proxies]] = [None]
_RESETS: List[Callable[[], None]] = []  # each proxy class's forget-everything, registered at import


def process_proxies() -> Proxies:
    """The process-wide connections (a RosProxies made on first use unless one was installed)."""
    with _LOCK:
        hub = _PROCESS[0]
        if hub is None:
            from flex_nav.ros.proxies import RosProxies  # noqa: PLC0415  (ROS only when FlexBE code reaches ROS)

            hub = _PROCESS[0] = RosProxies()
        return hub


def use_process_proxies(hub: Optional[Proxies]) -> None:
    """Install ``hub`` as the process-wide connections (None: make a RosProxies on next use); the proxies' cached
    state is forgotten."""
    reset_process_proxies()
    with _LOCK:
        _PROCESS[0] = hub


def reset_process_proxies() -> None:
    """Forget the process-wide connections and the proxies' caches (a RosProxies made here is shut down)."""
    with _LOCK:
        hub, _PROCESS[0] = _PROCESS[0], None
    shutdown = getattr(hub, "shutdown", None)
    if callable(shutdown):
        shutdown()
    for reset in list(_RESETS):
        reset()


def on_reset(reset: Callable[[], None]) -> Callable[[], None]:
    """Register a proxy class's forget-everything (called by :func:`reset_process_proxies`)."""
    _RESETS.append(reset)
    return reset


__all__ = ["on_reset", "process_proxies", "reset_process_proxies", "use_process_proxies"]
