"""A behavior's structure drawn as SVG: dot text written here, laid out by Graphviz's ``dot`` (a subprocess).

Containers (state machines, sub-behaviors, concurrency, priority) are nested clusters with their outcomes as
ovals on the inside of their border; leaf states are rounded boxes; edges are transitions labelled with their
outcome and the autonomy they need when it is not off (``[high]``); a concurrency container's conditions are
diamonds fed by the (state, outcome) pairs they AND. A folded container is drawn as one box.

Every element the page updates has an SVG id derived from the state's path (:func:`svg_id`): the state or
container itself, ``<id>.o.<outcome>`` for a container's outcome, ``<id>.e.<outcome>`` for the edge of an
outcome. The ids are an injective encoding (ASCII letters and digits kept, ``/`` as ``-``, any other character as
``_`` and six hex digits), so two paths never share one, and no label text reaches an id or a dot keyword.
"""

from __future__ import annotations

import shutil
import subprocess
from typing import AbstractSet, Dict, List, Optional, Tuple

from flex_nav.console.errors import GraphvizError
from flex_nav.console.model import BehaviorStructure, StateInfo
from flex_nav.exceptions import TimedOutError

DOT_TIMEOUT_S = 10.0  # [s] bound on one layout (explore, 60 states: about 0.3 s)
LEVEL_NAMES = ("off", "low", "high", "full")
STYLE = {  # cluster look per kind
    "state_machine": 'style="rounded"; color="#555555"',
    "sub_behavior": 'style="rounded,filled"; fillcolor="#f4f7fb"; color="#4a6fa5"',
    "concurrency": 'style="dashed"; color="#555555"',
    "priority": 'style="bold"; color="#b03030"',
}


def _encode(text: str) -> str:
    return "".join(c if c.isascii() and c.isalnum() else "-" if c == "/" else f"_{ord(c):06x}" for c in text)


def svg_id(path: str) -> str:
    """The SVG id of the state or container at ``path`` (``/`` -> ``st-``, ``/A/B`` -> ``st-A-B``)."""
    return "st" + _encode(path)


def outcome_id(path: str, outcome: str) -> str:
    """The SVG id of outcome ``outcome`` of the container at ``path``."""
    return f"{svg_id(path)}.o.{_encode(outcome)}"


def edge_id(path: str, outcome: str) -> str:
    """The SVG id of the edge taken when the state at ``path`` finishes with ``outcome``."""
    return f"{svg_id(path)}.e.{_encode(outcome)}"


def _quote(text: str) -> str:
    """A dot string literal shown as written (Graphviz reads ``&name;`` as an entity); a newline breaks the line."""
    text = text.replace("&", "&amp;").replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{text}"'


def _short_class(state: StateInfo) -> str:
    return state.class_name.rsplit(".", 1)[-1]


class _Writer:
    def __init__(self, structure: BehaviorStructure, folded: AbstractSet[str]) -> None:
        self.structure = structure
        self.folded = folded
        self.lines: List[str] = []

    def is_cluster(self, state: StateInfo) -> bool:
        return state.is_container and state.path not in self.folded

    def entry(self, state: StateInfo) -> Tuple[str, Optional[str]]:
        """(node an incoming edge points to, cluster it clips at) for ``state``."""
        if not self.is_cluster(state):
            return svg_id(state.path), None
        first = state.initial if state.initial is not None else (state.children[0] if state.children else None)
        child = self.structure.state(state.child_path(first)) if first is not None else None
        if child is None:
            return outcome_id(state.path, state.outcomes[0]) if state.outcomes else svg_id(state.path), None
        return self.entry(child)[0], f"cluster{svg_id(state.path)}"

    def emit(self, state: StateInfo, indent: str) -> Dict[str, str]:
        """Write ``state``; the node each of its outcomes' edges starts from."""
        sid = svg_id(state.path)
        name = state.label
        if not self.is_cluster(state):
            if state.is_container:
                label = f"{name}\n{state.behavior or state.kind.replace('_', ' ')} (folded)"
                look = 'shape=box, style="rounded,bold"'
            else:
                label = f"{name}\n{_short_class(state)}"
                look = 'shape=box, style="rounded,filled", fillcolor="#ffffff"'
            self.lines.append(f"{indent}{_quote(sid)} [id={_quote(sid)}, {look}, label={_quote(label)}];")
            return dict.fromkeys(state.outcomes, sid)
        kind = state.behavior if state.kind == "sub_behavior" else state.kind.replace("_", " ")
        kind = "behavior" if state.parent is None else kind
        inner = indent + "  "
        self.lines.append(f"{indent}subgraph {_quote('cluster' + sid)} {{")
        self.lines.append(f"{inner}id={_quote(sid)}; label={_quote(f'{name} ({kind})')}; {STYLE[state.kind]};")
        ends = {}
        for outcome in state.outcomes:
            oid = outcome_id(state.path, outcome)
            ends[outcome] = oid
            self.lines.append(f'{inner}{_quote(oid)} [id={_quote(oid)}, shape=oval, style=filled, '
                              f'fillcolor="#eeeeee", label={_quote(outcome)}];')
        starts: Dict[str, Dict[str, str]] = {}
        for label in state.children:
            child = self.structure.state(state.child_path(label))
            if child is not None:
                starts[label] = self.emit(child, inner)
        if state.kind == "concurrency":
            self.conditions(state, starts, ends, inner)
        else:
            self.transitions(state, starts, ends, inner)
        self.lines.append(f"{indent}}}")
        return ends

    def transitions(self, state: StateInfo, starts: Dict[str, Dict[str, str]], ends: Dict[str, str],
                    indent: str) -> None:
        for label, tails in starts.items():
            child = self.structure.state(state.child_path(label))
            assert child is not None
            for outcome, target in child.transitions.items():
                if outcome not in tails:
                    continue
                clip: Optional[str] = None
                if target in ends:
                    head = ends[target]
                else:
                    target_state = self.structure.state(state.child_path(target))
                    if target_state is None:
                        continue  # the runner validated the behavior; an unknown target is not drawn
                    head, clip = self.entry(target_state)
                level = child.autonomy.get(outcome, 0)
                text = outcome if level == 0 else f"{outcome} [{LEVEL_NAMES[level]}]"
                attrs = [f"id={_quote(edge_id(child.path, outcome))}", f"label={_quote(text)}"]
                if clip is not None:
                    attrs.append(f"lhead={_quote(clip)}")
                self.lines.append(f"{indent}{_quote(tails[outcome])} -> {_quote(head)} [{', '.join(attrs)}];")

    def conditions(self, state: StateInfo, starts: Dict[str, Dict[str, str]], ends: Dict[str, str],
                   indent: str) -> None:
        for index, (outcome, pairs) in enumerate(state.conditions):
            cid = f"{svg_id(state.path)}.c.{index}"
            text = "and" if len(pairs) > 1 else ""
            self.lines.append(f"{indent}{_quote(cid)} [id={_quote(cid)}, shape=diamond, label={_quote(text)}];")
            for label, child_outcome in pairs:
                tail = starts.get(label, {}).get(child_outcome)
                if tail is not None:
                    eid = edge_id(state.child_path(label), child_outcome)
                    self.lines.append(f"{indent}{_quote(tail)} -> {_quote(cid)} [id={_quote(eid)}, "
                                      f"label={_quote(child_outcome)}];")
            if outcome in ends:
                self.lines.append(f"{indent}{_quote(cid)} -> {_quote(ends[outcome])};")


def to_dot(structure: BehaviorStructure, folded: AbstractSet[str] = frozenset()) -> str:
    """Graphviz dot text of ``structure``; containers whose path is in ``folded`` are drawn as one box."""
    lines = [f"digraph {_quote(structure.behavior or 'none')} {{",
             '  compound=true; rankdir=TB; bgcolor="transparent"; fontname="Helvetica"; fontsize=11;',
             '  node [fontname="Helvetica", fontsize=10]; edge [fontname="Helvetica", fontsize=9];']
    root = structure.state("/")
    if root is None:
        lines.append('  "none" [id="none", shape=plaintext, label="no behavior loaded"];')
    else:
        writer = _Writer(structure, folded)
        writer.emit(root, "  ")
        lines.extend(writer.lines)
    lines.append("}")
    return "\n".join(lines) + "\n"


def render_svg(dot_text: str, dot: Optional[str] = None, timeout_s: float = DOT_TIMEOUT_S) -> str:
    """SVG of ``dot_text`` laid out by Graphviz (``dot``: its executable, else found on PATH), from ``<svg`` on.

    GraphvizError when dot is missing or fails (its message), TimedOutError after ``timeout_s`` [s]."""
    program = dot or shutil.which("dot")
    if program is None:
        raise GraphvizError("Graphviz's dot is not installed, so the console cannot draw behaviors: install the "
                            "Debian package graphviz (tools/install.sh does)")
    try:
        done = subprocess.run([program, "-Tsvg"], input=dot_text, text=True, capture_output=True,
                              timeout=timeout_s, check=False)
    except subprocess.TimeoutExpired as err:
        raise TimedOutError(f"dot did not lay the graph out within {timeout_s:g} s") from err
    except OSError as err:
        raise GraphvizError(f"cannot run Graphviz's dot ({program}): {err}") from err
    start = done.stdout.find("<svg")
    if done.returncode != 0 or start < 0:
        detail = done.stderr.strip().splitlines()[-3:] or [f"exit status {done.returncode}"]
        raise GraphvizError(f"Graphviz's dot failed: {' / '.join(detail)}")
    return done.stdout[start:]
