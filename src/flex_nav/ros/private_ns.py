"""The private namespace (``~``) of a node, or of one component when several components share a process.

A node started alone resolves ``~x`` to ``/<ns>/<node name>/x``, as rospy does. The ``navigation`` node hosts
get_path_server, follow_path_server, the controllers, ... in one process; each is built inside
:func:`hosted_as`, so its ``~x`` resolves to ``/<ns>/<component>/x`` -- the same names, parameters, topics,
actions and services as when it runs as a node of that name.

Components resolve their private names while they are built (their constructors), never later from callback
threads: the component's namespace is a :class:`contextvars.ContextVar` of the building thread only.
"""

from __future__ import annotations

import contextlib
import re
from contextvars import ContextVar
from typing import Iterator, Optional

import rospy

from flex_nav.exceptions import ConfigError

_COMPONENT_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")  # a ROS base name: no namespace, no "~"
_hosted: ContextVar[Optional[str]] = ContextVar("flex_nav_hosted_component", default=None)


def private_namespace() -> str:
    """The resolved private namespace: the hosted component's (``/robot1/get_path_server``) while one is being
    built, else the node's own name."""
    hosted = _hosted.get()
    return hosted if hosted is not None else rospy.get_name()


def private_name(name: str) -> str:
    """``name`` with a leading ``~`` resolved to the namespace of the component being built; outside one, and for
    other names, ``name`` unchanged (rospy resolves ``~`` against the node's name, and relative names against the
    node's namespace, which every hosted component shares)."""
    hosted = _hosted.get()
    if hosted is None or not name.startswith("~"):
        return name
    rest = name[1:].lstrip("/")
    return f"{hosted.rstrip('/')}/{rest}" if rest else hosted


@contextlib.contextmanager
def hosted_as(component: str) -> Iterator[str]:
    """Build a component inside this block to give it the private namespace ``<node namespace>/<component>``;
    yields that namespace. ``component`` must be a plain ROS base name (ConfigError otherwise)."""
    if not isinstance(component, str) or not _COMPONENT_NAME.match(component):
        raise ConfigError(f"component name {component!r} is not a ROS base name (a letter, then letters, digits, _)")
    namespace = rospy.get_namespace().rstrip("/") + "/" + component
    token = _hosted.set(namespace)
    try:
        yield namespace
    finally:
        _hosted.reset(token)
