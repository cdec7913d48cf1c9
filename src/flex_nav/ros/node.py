"""Starting a node without ever hanging: ``rospy.init_node`` with no master waits forever."""

from __future__ import annotations

import os
import sys
import time
from typing import Callable

import rospy

from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.ros.master_probe import master_is_up

MASTER_WAIT_S = 10.0  # [s] default bound on waiting for the master before a node gives up


def wait_for_master(timeout_s: float = MASTER_WAIT_S) -> str:
    """Return ROS_MASTER_URI once its master answers; raise NotReadyError after ``timeout_s`` [s]."""
    uri = os.environ.get("ROS_MASTER_URI", "")
    if not uri:
        raise NotReadyError("ROS_MASTER_URI is not set; start roscore and export ROS_MASTER_URI=http://HOST:PORT/")
    deadline = time.monotonic() + timeout_s
    while not master_is_up(uri):
        if time.monotonic() >= deadline:
            raise NotReadyError(
                f"no ROS master answers at ROS_MASTER_URI={uri} after {timeout_s:.0f} s; "
                "start roscore there or point ROS_MASTER_URI at a running master"
            )
        time.sleep(0.1)
    return uri


def init_node(name: str, master_timeout_s: float = MASTER_WAIT_S, anonymous: bool = False) -> None:
    """``rospy.init_node`` after a bounded wait for the master; exits with status 2 and a message if none."""
    try:
        wait_for_master(master_timeout_s)
    except NotReadyError as err:
        print(f"[{name}] ERROR: {err}", file=sys.stderr)
        sys.exit(2)
    rospy.init_node(name, anonymous=anonymous)


def run_node(name: str, factory: Callable[[], object]) -> int:
    """Start node ``name``, build its object with ``factory()``, spin; exit status 2 on a configuration error.

    A bad parameter (:class:`ConfigError`) is reported once with its reason and the node exits instead of
    running half-configured.
    """
    init_node(name)
    try:
        keep = factory()
    except ConfigError as err:
        rospy.logfatal(f"{rospy.get_name()}: {err}")
        print(f"[{rospy.get_name()}] configuration error: {err}", file=sys.stderr)
        return 2
    rospy.spin()
    del keep
    return 0
