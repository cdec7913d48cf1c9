"""A runner's ``~userdata`` JSON (schema of :mod:`flex_nav.behavior.userdata_summary`) read strictly, as the page's
``userdata`` event: ``robot``, ``behavior``, ``stamp`` and ``states`` ({path: [{key, role, set, text}]}), each
value already written as one short line of text (the page shows it with textContent; nothing is evaluated).

The text comes over ROS from any node that publishes on the topic: it is bounded (``MAX_USERDATA_CHARS``), every
field is checked, and a message that does not follow the schema is a :class:`~flex_nav.console.errors.UserdataError`
naming the field.
"""

from __future__ import annotations

import json
import math
from typing import Any, Dict, List

from flex_nav.behavior.userdata_summary import SCHEMA, VERSION
from flex_nav.console.errors import UserdataError

MAX_USERDATA_CHARS = 256 * 1024  # a longer message is refused (the runner's own limit is 16 000 characters)
MAX_TEXT_CHARS = 300  # one value's text on the page
MAX_DEPTH = 6  # nesting written out; deeper parts are "…"
ROLES = ("in", "out", "in/out")


def _number(value: float) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def value_text(value: Any, depth: int = 0) -> str:  # noqa: PLR0911  (one return per kind of summary)
    """One summary (see the schema) as a line of text, e.g. ``geometry_msgs/PoseStamped frame="map" x=7 y=1
    yaw_deg=90``; not cut (:func:`shown` cuts)."""
    if depth > MAX_DEPTH:
        return "…"
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return _number(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return "[" + ", ".join(value_text(v, depth + 1) for v in value) + "]"
    if not isinstance(value, dict):
        return f"<{type(value).__name__}>"
    kind = value.get("type")
    rest = {k: v for k, v in value.items() if k != "type"}
    if not isinstance(kind, str):
        return "{" + ", ".join(f"{k}: {value_text(v, depth + 1)}" for k, v in value.items()) + "}"
    if kind == "str" and isinstance(rest.get("head"), str):
        return f"{json.dumps(rest['head'], ensure_ascii=False)}… ({rest.get('len')} characters)"
    if kind == "float" and "value" in rest:
        return str(rest["value"])
    if kind in ("list", "tuple", "set", "dict") and "items" in rest:
        return _container_text(kind, rest, depth)
    fields = " ".join(f"{k}={value_text(v, depth + 1)}" for k, v in rest.items())
    return f"{kind} {fields}" if fields else kind


def _container_text(kind: str, rest: Dict[str, Any], depth: int) -> str:
    items = rest["items"]
    if isinstance(items, dict):
        inner = ", ".join(f"{json.dumps(k, ensure_ascii=False)}: {value_text(v, depth + 1)}" for k, v in items.items())
        count, braces = len(items), "{}"
    elif isinstance(items, list):
        inner = ", ".join(value_text(v, depth + 1) for v in items)
        count, braces = len(items), "[]"
    else:
        inner, count, braces = "?", 0, "[]"
    length = rest.get("len")
    more = f", … ({length} items)" if isinstance(length, int) and length > count else ""
    return f"{kind} {braces[0]}{inner}{more}{braces[1]}"


def shown(value: Any, limit: int = MAX_TEXT_CHARS) -> str:
    """:func:`value_text`, cut to ``limit`` characters."""
    text = value_text(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _field(data: Dict[str, Any], key: str, kind: type, where: str) -> Any:
    if key not in data:
        raise UserdataError(f"{where} has no {key!r}")
    value = data[key]
    if not isinstance(value, kind) or (isinstance(value, bool) and kind is not bool):
        raise UserdataError(f"{where}.{key} must be {kind.__name__}, got {type(value).__name__}")
    return value


def userdata_event(robot: str, text: str, max_chars: int = MAX_USERDATA_CHARS) -> Dict[str, Any]:
    """The page's event for a runner's ``~userdata`` text; UserdataError naming what does not follow the schema."""
    if len(text) > max_chars:
        raise UserdataError(f"userdata: {len(text)} characters, more than the {max_chars} accepted")
    try:
        data = json.loads(text, parse_constant=_no_constant)
    except (ValueError, RecursionError) as err:
        raise UserdataError(f"userdata: not JSON ({err})") from err
    if not isinstance(data, dict):
        raise UserdataError(f"userdata must be an object, got {type(data).__name__}")
    schema, version = data.get("schema"), data.get("version")
    if schema != SCHEMA or version != VERSION:
        raise UserdataError(f"userdata: schema {schema!r} version {version!r} is not {SCHEMA!r} version {VERSION}")
    behavior = _field(data, "behavior", str, "userdata")
    stamp = data.get("stamp")
    if stamp is not None and (isinstance(stamp, bool) or not isinstance(stamp, (int, float))
                              or not math.isfinite(stamp)):
        raise UserdataError("userdata.stamp must be a number or null")
    states: Dict[str, List[Dict[str, Any]]] = {}
    for index, raw in enumerate(_field(data, "states", list, "userdata")):
        where = f"userdata.states[{index}]"
        if not isinstance(raw, dict):
            raise UserdataError(f"{where} must be an object")
        path = _field(raw, "path", str, where)
        if not path.startswith("/"):
            raise UserdataError(f"{where}.path {path[:80]!r} must start with '/'")
        keys = []
        for number, entry in enumerate(_field(raw, "keys", list, where)):
            at = f"{where}.keys[{number}]"
            if not isinstance(entry, dict):
                raise UserdataError(f"{at} must be an object")
            role = _field(entry, "role", str, at)
            if role not in ROLES:
                raise UserdataError(f"{at}.role {role[:20]!r} is not one of {', '.join(ROLES)}")
            has_value = _field(entry, "set", bool, at)
            keys.append({"key": _field(entry, "key", str, at)[:120], "role": role, "set": has_value,
                         "text": shown(entry.get("value")) if has_value else "(no value yet)"})
        omitted = raw.get("keys_omitted", 0)
        if isinstance(omitted, int) and not isinstance(omitted, bool) and omitted > 0:
            keys.append({"key": "…", "role": "", "set": False, "text": f"{omitted} more keys not shown"})
        states[path] = keys
    omitted_states = data.get("states_omitted", 0)
    return {"type": "userdata", "robot": robot, "behavior": behavior, "stamp": stamp, "states": states,
            "states_omitted": omitted_states if isinstance(omitted_states, int) and not isinstance(
                omitted_states, bool) else 0}


def _no_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a JSON number")
