"""Whether a string is a legal ROS graph name (topic, action or service), checked before anything subscribes.

ROS names: an optional leading ``/`` (global) or ``~`` (private), then tokens separated by single ``/``; each
token starts with a letter and holds letters, digits and ``_``. So ``..``, blanks, ``a//b``, a trailing ``/``
and an empty name are refused (rospy would accept some of them and wait forever on a topic nobody publishes).
"""

from __future__ import annotations

import re
from typing import Optional

_NAME_PART = r"[A-Za-z][A-Za-z0-9_]*"
_NAME_RE = re.compile(rf"^[/~]?{_NAME_PART}(/{_NAME_PART})*$")


def topic_name_problem(name: str) -> Optional[str]:
    """Why ``name`` is not a legal ROS graph name, or None."""
    if not name:
        return "the name is empty"
    if _NAME_RE.match(name):
        return None
    return (f"{name!r} is not a legal ROS name (tokens of letters, digits and '_', each starting with a letter, "
            "separated by single '/'; optionally a leading '/' or '~')")
