"""Asking a ROS master (or a node) over XML-RPC whether it is there and which process it is, each call bounded.

No rospy: used by nodes before ``init_node`` (which would wait forever for a missing master) and by the test
harness (:mod:`flex_nav.testing.private_master`).
"""

from __future__ import annotations

import http.client
import xmlrpc.client
from typing import Any

MASTER_CALL_TIMEOUT_S = 1.0  # [s] socket timeout of one XML-RPC probe


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout_s: float) -> None:
        super().__init__()
        self._timeout_s = timeout_s

    def make_connection(self, host: tuple[str, dict[str, str]] | str) -> http.client.HTTPConnection:
        connection = super().make_connection(host)
        connection.timeout = self._timeout_s
        return connection


def master_pid(uri: str, timeout_s: float = MASTER_CALL_TIMEOUT_S) -> int | None:
    """The process id the ROS master at ``uri`` reports (``getPid``) within ``timeout_s`` [s], else None."""
    proxy = xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(timeout_s))
    try:
        reply: Any = proxy.getPid("/flex_nav_probe")
    except (OSError, xmlrpc.client.Error):
        return None
    ok = isinstance(reply, list) and len(reply) == 3 and reply[0] == 1 and isinstance(reply[2], int)
    return int(reply[2]) if ok else None


def node_pid(master_uri: str, node_name: str, timeout_s: float = MASTER_CALL_TIMEOUT_S) -> int | None:
    """The process id that node ``node_name``, registered with the master at ``master_uri``, reports, else None
    (each of the two XML-RPC calls bounded by ``timeout_s`` [s]; a node answers ``getPid`` as the master does)."""
    proxy = xmlrpc.client.ServerProxy(master_uri, transport=_TimeoutTransport(timeout_s))
    try:
        reply: Any = proxy.lookupNode("/flex_nav_probe", node_name)
    except (OSError, xmlrpc.client.Error):
        return None
    found = isinstance(reply, list) and len(reply) == 3 and reply[0] == 1 and isinstance(reply[2], str)
    return master_pid(reply[2], timeout_s) if found else None


def master_is_up(uri: str, timeout_s: float = MASTER_CALL_TIMEOUT_S) -> bool:
    """True when a ROS master answers ``getPid`` at ``uri`` within ``timeout_s`` [s]."""
    return master_pid(uri, timeout_s) is not None
