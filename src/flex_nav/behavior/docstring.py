"""The state docstring convention (FlexBE's) and its parser.

A state class documents itself in its docstring, one marker per item::

    class Wait(State):
        '''Waits until a time has passed.

        -- wait_time_s  float   [s] How long to wait; continuation lines
                                are indented.

        ># start_time   float   [s] Input key: ...
        #> end_time     float   [s] Output key: ...

        <= done                 The time has passed.
        <= {outcomes}           One of the outcomes given in the ``outcomes`` parameter.
        '''

- ``-- name type text``: a constructor parameter;
- ``># key type text``: an input key; ``#> key type text``: an output key;
- ``<= outcome text``: an outcome; ``<= {param}`` says the outcomes are the values of list parameter
  ``param``.

Text before the first marker is the description. An item ends at a blank line or the next marker.
:func:`parse_state_doc` returns a :class:`StateDoc`; :func:`check_state_doc` compares it with the
class's constructor and with an instance's keys and outcomes (used by the tests to keep every state
of the package documented exactly).
"""

from __future__ import annotations

import inspect
from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence

from flex_nav.exceptions import ConfigError

_MARKERS = {"--": "params", ">#": "inputs", "#>": "outputs", "<=": "outcomes"}


class DocItem(NamedTuple):
    name: str
    type: str  # "" for outcomes
    text: str
    line: int  # 1-based line in the cleaned docstring


class StateDoc(NamedTuple):
    description: str
    params: List[DocItem]
    inputs: List[DocItem]
    outputs: List[DocItem]
    outcomes: List[DocItem]

    def names(self, kind: str) -> List[str]:
        items: List[DocItem] = getattr(self, kind)
        return [item.name for item in items]


def parse_state_doc(doc: Optional[str], owner: str = "state") -> StateDoc:
    """Parse a docstring in the convention above; ConfigError names the line of a malformed item."""
    lines = inspect.cleandoc(doc or "").splitlines()
    description: List[str] = []
    found: Dict[str, List[DocItem]] = {"params": [], "inputs": [], "outputs": [], "outcomes": []}
    current: Optional[List[Any]] = None  # [kind, name, type, text parts, line]
    seen_marker = False

    def close() -> None:
        nonlocal current
        if current is not None:
            kind, name, type_, parts, line = current
            found[kind].append(DocItem(name, type_, " ".join(parts).strip(), line))
        current = None

    for number, raw in enumerate(lines, start=1):
        stripped = raw.strip()
        marker = stripped[:2]
        kind = _MARKERS.get(marker, "") if len(stripped) >= 2 and (len(stripped) == 2 or stripped[2] == " ") else ""
        if kind:
            close()
            seen_marker = True
            fields = stripped[2:].split(None, 2 if kind != "outcomes" else 1)
            if not fields:
                raise ConfigError(f"{owner} docstring line {number}: {marker!r} needs a name")
            if kind == "outcomes":
                current = [kind, fields[0], "", fields[1:], number]
            else:
                if len(fields) < 2:
                    raise ConfigError(
                        f"{owner} docstring line {number}: '{marker} {fields[0]}' needs a type and a text"
                    )
                current = [kind, fields[0], fields[1], fields[2:], number]
        elif not stripped:
            close()
            if not seen_marker:
                description.append("")
        elif current is not None and raw[:1].isspace():
            current[3].append(stripped)
        elif not seen_marker:
            description.append(stripped)
        else:
            raise ConfigError(
                f"{owner} docstring line {number}: text after the items must be an indented continuation "
                f"of an item or follow a marker (--, >#, #>, <=): {stripped!r}"
            )
    close()
    return StateDoc(
        "\n".join(description).strip(), found["params"], found["inputs"], found["outputs"], found["outcomes"]
    )


def constructor_params(cls: type) -> List[str]:
    """Names of the constructor's parameters (no self, *args, **kwargs)."""
    signature = inspect.signature(cls.__init__)  # type: ignore[misc]
    return [
        name
        for name, param in signature.parameters.items()
        if name != "self" and param.kind not in (param.VAR_POSITIONAL, param.VAR_KEYWORD)
    ]


def check_state_doc(cls: type, instance: Any, params: Mapping[str, Any]) -> List[str]:
    """Problems (empty if none) between ``cls``'s docstring and its constructor, keys and outcomes.

    ``instance`` is ``cls(**params)``; ``params`` is used to expand ``<= {param}`` outcomes.
    """
    problems: List[str] = []
    name = cls.__name__
    try:
        doc = parse_state_doc(cls.__doc__, name)
    except ConfigError as err:
        return [str(err)]
    if not doc.description:
        problems.append(f"{name}: the docstring has no description")
    _compare(problems, name, "constructor parameters (--)", doc.names("params"), constructor_params(cls))
    _compare(problems, name, "input keys (>#)", doc.names("inputs"), list(instance.input_keys))
    _compare(problems, name, "output keys (#>)", doc.names("outputs"), list(instance.output_keys))
    documented: List[str] = []
    for outcome in doc.names("outcomes"):
        if outcome.startswith("{") and outcome.endswith("}"):
            source = outcome[1:-1]
            if source not in params:
                problems.append(f"{name}: outcome item {outcome} names no constructor parameter")
                continue
            documented.extend(str(o) for o in params[source])
        else:
            documented.append(outcome)
    _compare(problems, name, "outcomes (<=)", documented, list(instance.outcomes))
    for item in (*doc.params, *doc.inputs, *doc.outputs, *doc.outcomes):
        if not item.text:
            problems.append(f"{name}: {item.name!r} (docstring line {item.line}) has no text")
    return problems


def _compare(problems: List[str], owner: str, what: str, documented: Sequence[str], actual: Sequence[str]) -> None:
    if list(documented) != list(actual):
        problems.append(f"{owner}: documented {what} {list(documented)} differ from the real ones {list(actual)}")
