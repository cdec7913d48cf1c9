"""Graphviz export: dot text names every state, transition and condition; PNG only when dot exists."""

from __future__ import annotations

from pathlib import Path

import pytest

from flex_nav.behavior.dot import dot_available, to_dot, write_png
from flex_nav.behavior.yaml_loader import load_behavior

DATA = Path(__file__).resolve().parent / "data"


def test_dot_text_of_a_behavior_with_all_container_kinds():
    behavior = load_behavior("guarded_wait", search_path=[DATA])
    text = behavior.to_dot()
    assert text.startswith('digraph "guarded_wait" {')
    assert text.rstrip().endswith("}")
    assert text.count("{") == text.count("}")
    for label in ("Work\\nWait", "Monitor\\nWait", "Say\\nLog", "Pause\\nWait", "Idle\\nDecision"):
        assert f'label="{label}"' in text
    assert 'label="Guarded (concurrency container)"; style=dashed' in text
    assert 'label="Recover (priority container)"; style=solid; color=red' in text
    assert text.count("shape=diamond") == 2  # one per condition
    assert '[label="wait"]' in text and '[label="done"]' in text


def test_autonomy_appears_on_edges():
    text = to_dot(load_behavior(DATA / "count_loop.yaml").root, "count_loop")
    assert '[label="reached [high]"]' in text
    assert '[label="not_met"]' in text


def test_png_is_written_when_graphviz_is_installed_else_skipped(tmp_path):
    target = tmp_path / "count_loop.png"
    written = write_png(load_behavior(DATA / "count_loop.yaml").to_dot(), target)
    assert written is dot_available()
    if not written:
        assert not target.exists()
        pytest.skip("Graphviz 'dot' is not installed: PNG export skipped (dot text is tested above)")
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
