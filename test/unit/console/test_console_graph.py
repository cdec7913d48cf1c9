"""The console's SVG: every state has an id derived from its path, containers are clusters, folded containers one
box; dot runs as a bounded subprocess without a shell and fails clearly when it is missing or breaks."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Dict, List

import pytest
from unit.console.console_testlib import structure, structure_text

from flex_nav.console import graph
from flex_nav.console.errors import GraphvizError
from flex_nav.console.graph import edge_id, outcome_id, render_svg, svg_id, to_dot
from flex_nav.console.model import BehaviorStructure
from flex_nav.exceptions import TimedOutError

SVG = "{http://www.w3.org/2000/svg}"
needs_dot = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz's dot is not installed")


def groups(svg: str) -> Dict[str, Dict[str, Any]]:
    """id -> {class, texts} of every <g> of an SVG (ids decoded from XML, as the browser sees them)."""
    found = {}
    for g in ET.fromstring(svg).iter(f"{SVG}g"):
        texts = [t.text or "" for t in g.iter(f"{SVG}text")]
        found[g.get("id", "")] = {"class": g.get("class"), "texts": texts}
    return found


@needs_dot
@pytest.mark.parametrize("name", ["flex_planner", "explore"])
def test_every_state_has_its_id_and_every_container_is_a_cluster(name: str) -> None:
    loaded = structure(name)
    drawn = groups(render_svg(to_dot(loaded)))
    for state in loaded.states.values():
        assert drawn[svg_id(state.path)]["class"] == ("cluster" if state.is_container else "node"), state.path
        if state.is_container:
            for outcome in state.outcomes:
                assert drawn[outcome_id(state.path, outcome)]["class"] == "node"
    approve = "/ApprovePlan" if name == "flex_planner" else "/ApproveFrontier"
    outcome = "execute" if name == "flex_planner" else "explore"
    assert drawn[edge_id(approve, outcome)]["texts"] == [f"{outcome} [high]"]


@needs_dot
def test_labels_kinds_and_concurrency_conditions_are_drawn() -> None:
    drawn = groups(render_svg(to_dot(structure("flex_planner"))))
    assert drawn[svg_id("/")]["texts"] == ["flex_planner (behavior)"]
    assert drawn[svg_id("/Navigate")]["texts"] == ["Navigate (flex_navigate)"]
    assert drawn[svg_id("/Navigate/Navigate")]["texts"] == ["Navigate (concurrency)"]
    assert drawn[svg_id("/GetPath")]["texts"] == ["GetPath", "GetPathState"]
    assert drawn[edge_id("/Navigate/Navigate/Stuck", "stuck")]["texts"] == ["stuck"]  # into its condition
    diamonds = [i for i in drawn if re.fullmatch(re.escape(svg_id("/Navigate/Navigate")) + r"\.c\.\d+", i)]
    assert len(diamonds) == len(structure("flex_planner").states["/Navigate/Navigate"].conditions)


@needs_dot
def test_a_folded_container_is_one_box_without_its_states() -> None:
    drawn = groups(render_svg(to_dot(structure("flex_planner"), frozenset({"/Navigate"}))))
    assert drawn[svg_id("/Navigate")]["class"] == "node"
    assert drawn[svg_id("/Navigate")]["texts"] == ["Navigate", "flex_navigate (folded)"]
    assert svg_id("/Navigate/Navigate/Bumper") not in drawn and svg_id("/Recovery/Stop") in drawn
    assert drawn[edge_id("/Navigate", "bumper")]["class"] == "edge"  # its outcomes still lead on


def test_ids_are_injective_and_plain() -> None:
    paths = ["/", "/a", "/a/b", "/a-b", "/a_b", "/a b", "/a_00002d", "/a.b", "/Ä", "/a/b/"]
    ids = [svg_id(p) for p in paths]
    assert len(set(ids)) == len(paths)
    assert all(re.fullmatch(r"st[A-Za-z0-9_-]*", i) for i in ids)
    assert svg_id("/Navigate/FollowPath") == "st-Navigate-FollowPath"
    assert edge_id("/a", "b c") == "st-a.e.b_000020c" and outcome_id("/", "done") == "st-.o.done"


@needs_dot
def test_labels_with_quotes_backslashes_and_markup_stay_text() -> None:
    data = json.loads(structure_text("simple_recovery"))
    data["states"][0]["label"] = 'say "hi" \\ <b>&amp;'
    data["states"][1]["class"] = "m.Odd<script>"
    odd = BehaviorStructure.from_dict(data)
    svg = render_svg(to_dot(odd))
    drawn = groups(svg)
    assert drawn[svg_id("/")]["texts"] == ['say "hi" \\ <b>&amp; (behavior)']
    assert "<script>" not in svg and "<b>" not in svg


def test_no_behavior_loaded_draws_a_note() -> None:
    text = to_dot(structure(""))
    assert '"none" [id="none", shape=plaintext, label="no behavior loaded"]' in text


def test_a_missing_dot_is_a_clear_error(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setattr(graph.shutil, "which", lambda name: None)
    with pytest.raises(GraphvizError, match=r"dot is not installed.*graphviz"):
        render_svg("digraph {}")
    with pytest.raises(GraphvizError, match="cannot run Graphviz's dot"):
        render_svg("digraph {}", dot=str(tmp_path / "no-dot-here"))


@needs_dot
def test_dot_failing_is_reported() -> None:
    with pytest.raises(GraphvizError, match=r"dot failed: .*syntax error"):
        render_svg("digraph { a -> ")


def test_a_hanging_dot_is_stopped_at_the_timeout(tmp_path: Path) -> None:
    slow = tmp_path / "slow-dot"
    slow.write_text("#!/bin/sh\nsleep 10\n")
    slow.chmod(0o755)
    with pytest.raises(TimedOutError, match=r"within 0\.2 s"):
        render_svg("digraph {}", dot=str(slow), timeout_s=0.2)


def test_dot_runs_with_an_argument_list_and_no_shell(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: List[Any] = []

    def fake_run(args: Any, **kwargs: Any) -> subprocess.CompletedProcess:
        calls.append((args, kwargs))
        return subprocess.CompletedProcess(args, 0, stdout='<?xml version="1.0"?>\n<svg id="x"/>', stderr="")

    monkeypatch.setattr(graph.subprocess, "run", fake_run)
    assert render_svg("digraph {}", dot="/usr/bin/dot", timeout_s=3.0) == '<svg id="x"/>'
    ((args, kwargs),) = calls
    assert args == ["/usr/bin/dot", "-Tsvg"] and kwargs["input"] == "digraph {}" and kwargs["timeout"] == 3.0
    assert not kwargs.get("shell", False)
