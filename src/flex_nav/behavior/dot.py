"""Graphviz export of a behavior's structure: dot text always, PNG when ``dot`` is installed.

Containers are clusters (state machines solid, concurrency dashed, priority bold red); leaf states
are boxes labelled with their label and class; each container's outcomes are ovals at its border.
Edges are transitions labelled ``outcome`` plus the required autonomy when it is not OFF
(``[low]``, ``[high]``, ``[full]``). In a concurrency container, each condition is a diamond fed by
the ``(state, outcome)`` pairs it ANDs, leading to the container outcome it gives.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path
from typing import TYPE_CHECKING, Dict, List, Union

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.concurrency import ConcurrencyContainer
from flex_nav.behavior.container import Container
from flex_nav.behavior.priority import PriorityContainer
from flex_nav.behavior.state import State
from flex_nav.behavior.state_machine import StateMachine
from flex_nav.exceptions import TimedOutError

if TYPE_CHECKING:
    from flex_nav.behavior.behavior import Behavior

DOT_TIMEOUT_S = 30.0  # [s] bound on one `dot` run


def _quote(text: str) -> str:
    """A dot string literal; a newline in ``text`` becomes a line break of the label."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{escaped}"'


class _DotWriter:
    def __init__(self) -> None:
        self.lines: List[str] = []
        self.ids: Dict[int, str] = {}
        self.counter = 0

    def new_id(self, prefix: str) -> str:
        self.counter += 1
        return f"{prefix}{self.counter}"

    def entry(self, state: State, path: str) -> str:
        """The node an incoming edge of ``state`` points to (a container: its initial state)."""
        if isinstance(state, StateMachine):
            initial = state.initial_state
            return self.entry(state[initial], f"{path}/{initial}") if initial is not None else self.ids[id(state)]
        if isinstance(state, ConcurrencyContainer) and state.children:
            label, first = next(iter(state.children.items()))
            return self.entry(first, f"{path}/{label}")
        return self.ids[id(state)]

    def emit(self, state: State, path: str, indent: str) -> Dict[str, str]:  # noqa: PLR0912
        """Write ``state``; return the node ids of its outcomes (where its outgoing edges start)."""
        if not isinstance(state, Container):
            node = self.new_id("s")
            self.ids[id(state)] = node
            label = f"{path.rsplit('/', 1)[-1] or '/'}\n{type(state).__name__}"
            self.lines.append(f"{indent}{node} [shape=box, style=rounded, label={_quote(label)}];")
            return {outcome: node for outcome in state.outcomes}
        cluster = self.new_id("cluster_")
        self.ids[id(state)] = cluster
        style = "dashed" if isinstance(state, ConcurrencyContainer) else "solid"
        color = "red" if isinstance(state, PriorityContainer) else "black"
        title = f"{path.rsplit('/', 1)[-1] or '/'} ({state.kind})"
        self.lines.append(f"{indent}subgraph {cluster} {{")
        inner = indent + "  "
        self.lines.append(f"{inner}label={_quote(title)}; style={style}; color={color};")
        outcome_ids = {}
        for outcome in state.outcomes:
            oid = self.new_id("o")
            outcome_ids[outcome] = oid
            self.lines.append(f"{inner}{oid} [shape=oval, label={_quote(outcome)}];")
        starts: Dict[str, Dict[str, str]] = {}
        for label, child in state.children.items():
            starts[label] = self.emit(child, f"{path.rstrip('/')}/{label}", inner)
        if isinstance(state, StateMachine):
            for label in state.children:
                levels = state.autonomy_of(label)
                for outcome, target in state.transitions_of(label).items():
                    if target in outcome_ids:
                        head = outcome_ids[target]
                    elif target in state.children:
                        head = self.entry(state[target], f"{path.rstrip('/')}/{target}")
                    else:
                        continue  # invalid target: validate() reports it
                    level = levels.get(outcome, Autonomy.OFF)
                    text = outcome if level == Autonomy.OFF else f"{outcome} [{level.name.lower()}]"
                    self.lines.append(f"{inner}{starts[label][outcome]} -> {head} [label={_quote(text)}];")
        elif isinstance(state, ConcurrencyContainer):
            for outcome, pairs in state.conditions:
                cid = self.new_id("c")
                self.lines.append(f"{inner}{cid} [shape=diamond, label={_quote('and' if len(pairs) > 1 else '')}];")
                for label, child_outcome in pairs:
                    if label in starts and child_outcome in starts[label]:
                        tail = starts[label][child_outcome]
                        self.lines.append(f"{inner}{tail} -> {cid} [label={_quote(child_outcome)}];")
                if outcome in outcome_ids:
                    self.lines.append(f"{inner}{cid} -> {outcome_ids[outcome]};")
        self.lines.append(f"{indent}}}")
        return outcome_ids


def to_dot(root: State, name: str = "behavior") -> str:
    """Graphviz dot text of the tree under ``root``."""
    writer = _DotWriter()
    writer.lines.append(f"digraph {_quote(name)} {{")
    writer.lines.append("  compound=true; rankdir=TB; node [fontname=Helvetica]; edge [fontname=Helvetica];")
    writer.emit(root, "/", "  ")
    writer.lines.append("}")
    return "\n".join(writer.lines) + "\n"


def behavior_to_dot(behavior: Behavior) -> str:
    return to_dot(behavior.root, behavior.name)


def dot_available() -> bool:
    return shutil.which("dot") is not None


def write_png(dot_text: str, path: Union[str, Path]) -> bool:
    """Render ``dot_text`` to PNG at ``path`` with Graphviz; False (nothing written) if ``dot`` is missing."""
    dot = shutil.which("dot")
    if dot is None:
        return False
    try:
        subprocess.run(
            [dot, "-Tpng", "-o", str(path)],
            input=dot_text,
            text=True,
            check=True,
            capture_output=True,
            timeout=DOT_TIMEOUT_S,
        )
    except subprocess.TimeoutExpired as err:
        raise TimedOutError(f"dot did not render {path} within {DOT_TIMEOUT_S} s") from err
    return True
