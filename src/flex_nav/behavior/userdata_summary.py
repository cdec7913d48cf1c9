"""The userdata of a running behavior's active states as bounded JSON, for operator tools (the runner's ``~userdata``).

:func:`summarize` turns one value into a small JSON value without evaluating, pickling or printing anything of it:
numbers, booleans and ``None`` as they are; a string cut to ``max_string_chars``; containers as their type, length
and first ``max_items`` items; ROS messages (anything with the ``_type`` and ``__slots__`` of a generated message)
as their type and a few fields chosen per type (a ``PoseStamped``'s frame, x, y and yaw; a ``Path``'s pose count,
length and end; ...), other messages as their first fields; numpy arrays as shape and dtype; any other object as
its class name only (its ``repr`` could be huge, slow or secret). :func:`userdata_json` writes the runner's
message. The schema (``"schema": "flex_nav/userdata"``, ``"version": 1``)::

    {
      "schema": "flex_nav/userdata", "version": 1,
      "behavior": "flex_planner",     # "" when none runs (then "states" is [])
      "stamp": 12.5,                  # [s] the behavior's clock when the values were read
      "states": [STATE, ...],         # the active states, deepest first, then the containers above them, "/" last
      "states_omitted": 0             # active states left out to keep the message within max_message_chars
    }

    STATE = {"path": "/ReceiveGoal", "keys": [KEY, ...], "keys_omitted": 0}
    KEY = {"key": "goal",             # the state's own name for it (before remapping)
           "role": "in" | "out" | "in/out",
           "set": true,               # false: the container holds no value for it (yet); "value" is null
           "value": SUMMARY}

    SUMMARY = null | true | 1 | 2.5 | "text"
            | {"type": "str", "len": 5000, "head": "first characters"}          # a long string
            | {"type": "float", "value": "nan" | "inf" | "-inf"}
            | {"type": "list" | "tuple" | "set" | "dict", "len": 3, "items": [SUMMARY, ...] or {key: SUMMARY}}
            | {"type": "geometry_msgs/PoseStamped", "frame": "map", "x": 7.0, "y": 1.0, "yaw_deg": 90.0}
            | {"type": "nav_msgs/Path", "frame": "map", "poses": 120, "length_m": 6.1, "end": [7.0, 1.0]}
            | {"type": "ndarray", "shape": [3, 2], "dtype": "float64"} | {"type": "some.module.Class"} | ...
            | {"type": "...", "cut": "the first characters of its JSON"}   # a summary over max_value_chars

An output key is listed only once the container holds a value for it (the state wrote it, or an earlier state of
the same container did); an input key always, ``set`` false until it has a value.
"""

from __future__ import annotations

import collections
import dataclasses
import enum
import json
import math
import sys
from typing import Any, Callable, Dict, List, NamedTuple, Sequence, Tuple

from flex_nav.exceptions import ConfigError
from flex_nav.nav.pose_checks import yaw_of_quaternion

SCHEMA = "flex_nav/userdata"
VERSION = 1
MISSING = object()  # a key with no value in its container's store


@dataclasses.dataclass(frozen=True)
class SummaryLimits:
    """How much of the userdata is shown (each bound > 0; ConfigError naming the bad one)."""

    max_value_chars: int = 400  # JSON characters of one key's summary
    max_message_chars: int = 16_000  # characters of a whole message
    max_string_chars: int = 120  # characters of a string shown
    max_items: int = 6  # items of a container, fields of a message
    max_depth: int = 3  # nesting shown; deeper values are given by their type only
    max_keys: int = 32  # keys of one state
    max_states: int = 64  # active states

    def __post_init__(self) -> None:
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ConfigError(f"userdata summary limit {field.name} must be an integer >= 1, got {value!r}")


DEFAULT_LIMITS = SummaryLimits()


class StateUserdata(NamedTuple):
    """One active state's declared keys and the values its container holds for them now (the objects themselves;
    ``MISSING`` for none). ``inputs`` and ``outputs`` are ``(key, value)`` pairs in declaration order."""

    path: str
    inputs: Tuple[Tuple[str, Any], ...]
    outputs: Tuple[Tuple[str, Any], ...]


def _number(value: float) -> Any:
    if math.isfinite(value):
        return float(f"{value:.6g}")
    return {"type": "float", "value": "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")}


def _type_name(value: Any) -> str:
    kind = type(value)
    return kind.__qualname__ if kind.__module__ == "builtins" else f"{kind.__module__}.{kind.__qualname__}"


def _is_ros_message(value: Any) -> bool:
    kind = type(value)
    return isinstance(getattr(kind, "_type", None), str) and isinstance(getattr(kind, "__slots__", None),
                                                                        (list, tuple))


def _yaw_deg(q: Any) -> Any:
    return _number(math.degrees(yaw_of_quaternion(float(q.x), float(q.y), float(q.z), float(q.w))))


def _pose(pose: Any) -> Dict[str, Any]:
    return {"x": _number(float(pose.position.x)), "y": _number(float(pose.position.y)),
            "yaw_deg": _yaw_deg(pose.orientation)}


def _frame(msg: Any) -> str:
    return str(msg.header.frame_id)[:80]


def _path(msg: Any) -> Dict[str, Any]:
    points = [(float(p.pose.position.x), float(p.pose.position.y)) for p in msg.poses]
    length = sum(math.dist(a, b) for a, b in zip(points, points[1:]))
    summary: Dict[str, Any] = {"frame": _frame(msg), "poses": len(points), "length_m": _number(length)}
    if points:
        summary["end"] = [_number(points[-1][0]), _number(points[-1][1])]
    return summary


# per message type: the fields shown (a message's header is shown as its frame)
_MESSAGES: Dict[str, Callable[[Any], Dict[str, Any]]] = {
    "geometry_msgs/PoseStamped": lambda m: {"frame": _frame(m), **_pose(m.pose)},
    "geometry_msgs/Pose": _pose,
    "geometry_msgs/PoseWithCovarianceStamped": lambda m: {"frame": _frame(m), **_pose(m.pose.pose)},
    "geometry_msgs/PoseWithCovariance": lambda m: _pose(m.pose),
    "geometry_msgs/Pose2D": lambda m: {"x": _number(m.x), "y": _number(m.y), "yaw_deg": _number(math.degrees(m.theta))},
    "geometry_msgs/Point": lambda m: {"x": _number(m.x), "y": _number(m.y), "z": _number(m.z)},
    "geometry_msgs/Point32": lambda m: {"x": _number(m.x), "y": _number(m.y), "z": _number(m.z)},
    "geometry_msgs/Vector3": lambda m: {"x": _number(m.x), "y": _number(m.y), "z": _number(m.z)},
    "geometry_msgs/Quaternion": lambda m: {"yaw_deg": _yaw_deg(m)},
    "geometry_msgs/Twist": lambda m: {"vx": _number(m.linear.x), "wz": _number(m.angular.z)},
    "geometry_msgs/TwistStamped": lambda m: {"frame": _frame(m), "vx": _number(m.twist.linear.x),
                                             "wz": _number(m.twist.angular.z)},
    "geometry_msgs/PoseArray": lambda m: {"frame": _frame(m), "poses": len(m.poses)},
    "geometry_msgs/PolygonStamped": lambda m: {"frame": _frame(m), "points": len(m.polygon.points)},
    "nav_msgs/Path": _path,
    "nav_msgs/Odometry": lambda m: {"frame": _frame(m), **_pose(m.pose.pose), "v": _number(m.twist.twist.linear.x)},
    "nav_msgs/OccupancyGrid": lambda m: {"frame": _frame(m), "width": int(m.info.width), "height": int(m.info.height),
                                         "resolution": _number(m.info.resolution)},
    "sensor_msgs/LaserScan": lambda m: {"frame": _frame(m), "ranges": len(m.ranges)},
}


class _Summarizer:
    def __init__(self, limits: SummaryLimits) -> None:
        self.limits = limits

    def value(self, value: Any, depth: int) -> Any:  # noqa: PLR0911, PLR0912  (one return per kind of value)
        if value is None or isinstance(value, bool):
            return value
        if isinstance(value, enum.Enum):
            return {"type": type(value).__qualname__, "name": str(value.name)[: self.limits.max_string_chars]}
        if isinstance(value, int):
            return int(value) if abs(value) < 2**53 else {"type": "int", "digits": len(str(abs(value)))}
        if isinstance(value, float):
            return _number(float(value))
        if isinstance(value, str):
            cut = self.limits.max_string_chars
            return str(value) if len(value) <= cut else {"type": "str", "len": len(value), "head": value[:cut]}
        if isinstance(value, (bytes, bytearray, memoryview)):
            return {"type": type(value).__name__, "len": len(value)}
        numpy = sys.modules.get("numpy")
        if numpy is not None and isinstance(value, numpy.generic):
            return self.value(value.item(), depth)
        if numpy is not None and isinstance(value, numpy.ndarray):
            return self._array(value, depth)
        if depth >= self.limits.max_depth:
            return {"type": value._type if _is_ros_message(value) else _type_name(value)}
        if _is_ros_message(value):
            return self._message(value, depth)
        if isinstance(value, tuple) and hasattr(value, "_fields"):  # a named tuple
            return self._fields(value, [str(f) for f in value._fields], depth)
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            return self._fields(value, [f.name for f in dataclasses.fields(value)], depth)
        if isinstance(value, (dict, collections.abc.Mapping)):
            return self._mapping(value, depth)
        if isinstance(value, (list, tuple, set, frozenset, collections.deque)):
            return self._sequence(value, depth)
        return {"type": _type_name(value)}

    def _array(self, value: Any, depth: int) -> Dict[str, Any]:
        summary: Dict[str, Any] = {"type": "ndarray", "shape": [int(n) for n in value.shape], "dtype": str(value.dtype)}
        if value.ndim == 1 and value.size <= self.limits.max_items and depth < self.limits.max_depth:
            summary["items"] = [self.value(v, depth + 1) for v in value.tolist()]
        return summary

    def _sequence(self, value: Any, depth: int) -> Dict[str, Any]:
        kind = "list" if isinstance(value, (list, collections.deque)) else type(value).__name__
        if isinstance(value, (set, frozenset)):
            kind = "set"
        items = []
        for index, item in enumerate(value):
            if index >= self.limits.max_items:
                break
            items.append(self.value(item, depth + 1))
        return {"type": kind, "len": len(value), "items": items}

    def _mapping(self, value: Any, depth: int) -> Dict[str, Any]:
        items: Dict[str, Any] = {}
        for index, key in enumerate(value):
            if index >= self.limits.max_items:
                break
            name = key if isinstance(key, str) else (repr(key) if isinstance(key, (int, float, bool)) else
                                                      f"<{_type_name(key)}>")
            items[name[:60]] = self.value(value[key], depth + 1)
        return {"type": "dict", "len": len(value), "items": items}

    def _fields(self, value: Any, names: Sequence[str], depth: int) -> Dict[str, Any]:
        summary: Dict[str, Any] = {"type": type(value).__qualname__}
        for name in names[: self.limits.max_items]:
            if name != "type":
                summary[name] = self.value(getattr(value, name), depth + 1)
        return summary

    def _message(self, msg: Any, depth: int) -> Dict[str, Any]:
        kind = str(msg._type)
        special = _MESSAGES.get(kind)
        if special is not None:
            return {"type": kind, **special(msg)}
        summary: Dict[str, Any] = {"type": kind}
        for name in list(type(msg).__slots__)[: self.limits.max_items]:
            if name == "header":
                summary["frame"] = _frame(msg)
            elif name != "type":
                summary[name] = self.value(getattr(msg, name), depth + 1)
        return summary


def summarize(value: Any, limits: SummaryLimits = DEFAULT_LIMITS) -> Any:
    """A JSON value describing ``value`` within ``limits`` (see the module doc); never raises: a value that cannot
    be read (a message changed while it was read, a field of the wrong type) is given as its type and the error."""
    summary: Any
    try:
        summary = _Summarizer(limits).value(value, 0)
        text = json.dumps(summary, separators=(",", ":"), allow_nan=False)
    except (AttributeError, TypeError, ValueError, RuntimeError, RecursionError, OverflowError) as err:
        return {"type": _type_name(value), "error": f"{type(err).__name__}: {err}"[: limits.max_string_chars]}
    if len(text) <= limits.max_value_chars:
        return summary
    kind = summary.get("type", _type_name(value)) if isinstance(summary, dict) else _type_name(value)
    return {"type": kind, "cut": text[: limits.max_value_chars]}


def _state_entry(state: StateUserdata, limits: SummaryLimits) -> Dict[str, Any]:
    outputs = dict(state.outputs)
    keys: List[Dict[str, Any]] = []
    for key, value in state.inputs:
        keys.append({"key": key, "role": "in/out" if key in outputs else "in", "set": value is not MISSING,
                     "value": None if value is MISSING else summarize(value, limits)})
    read = {key for key, _ in state.inputs}
    for key, value in state.outputs:
        if key not in read and value is not MISSING:
            keys.append({"key": key, "role": "out", "set": True, "value": summarize(value, limits)})
    return {"path": state.path, "keys": keys[: limits.max_keys], "keys_omitted": max(0, len(keys) - limits.max_keys)}


def userdata_message(behavior: str, stamp: float, states: Sequence[StateUserdata],
                     limits: SummaryLimits = DEFAULT_LIMITS) -> Dict[str, Any]:
    """The message for ``states`` (see the module doc), at most ``limits.max_message_chars`` long as JSON: states
    that do not fit are counted in ``states_omitted``, deepest paths first kept."""
    ordered = sorted(states, key=lambda s: (-s.path.rstrip("/").count("/"), s.path))  # the root ("/") last
    message: Dict[str, Any] = {"schema": SCHEMA, "version": VERSION, "behavior": behavior,
                               "stamp": _number(stamp) if math.isfinite(stamp) else None, "states": [],
                               "states_omitted": 0}
    used = len(json.dumps(message, separators=(",", ":"))) + 16  # room for the omitted count's digits
    for state in ordered[: limits.max_states]:
        entry = _state_entry(state, limits)
        size = len(json.dumps(entry, separators=(",", ":"))) + 1
        if used + size > limits.max_message_chars:
            message["states_omitted"] += 1
            continue
        message["states"].append(entry)
        used += size
    message["states_omitted"] += max(0, len(ordered) - limits.max_states)
    return message


def userdata_json(behavior: str, stamp: float, states: Sequence[StateUserdata],
                  limits: SummaryLimits = DEFAULT_LIMITS) -> str:
    """:func:`userdata_message` as JSON text."""
    return json.dumps(userdata_message(behavior, stamp, states, limits), separators=(",", ":"), allow_nan=False)
