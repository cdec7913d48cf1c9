"""Structures of the shipped behaviors, as a runner publishes them, for the console's tests."""

from __future__ import annotations

import functools
from pathlib import Path

from flex_nav.behavior.structure import structure_json
from flex_nav.behavior.yaml_loader import load_behavior
from flex_nav.console.model import BehaviorStructure

BEHAVIORS = Path(__file__).resolve().parents[3] / "behaviors"


@functools.lru_cache(maxsize=None)
def structure_text(name: str) -> str:
    """The ~structure JSON of behavior ``name`` loaded from behaviors/ ("" : no behavior loaded)."""
    behavior = load_behavior(name, search_path=[BEHAVIORS]) if name else None
    return structure_json(behavior, [BEHAVIORS])


def structure(name: str) -> BehaviorStructure:
    return BehaviorStructure.from_json(structure_text(name))
