"""The held-out models of the classifier's dataset: twelve sets of people, pushable objects and furniture (the
``unseen`` .. ``unseen12`` splits, one module each), each defined, rendered and measured before the training data
that followed it, and never used in a training or selection split (``test/unit/perception/test_dataset_tools.py``).

Each builder is registered with ``@held_out(split, label, model)`` (:mod:`.registry`); the tables below are read
from the registry once every set's module is imported. Frozen: changing a builder (or the order of a set's
builders) changes a stored held-out split, so a new held-out set is a new module, imported here. What more than one
set builds is in :mod:`.common`.
"""

from __future__ import annotations

from typing import Dict, Tuple

from tools.perception.held_out import (  # noqa: F401  (importing a set's module registers its builders)
    unseen,
    unseen2,
    unseen3,
    unseen4,
    unseen5,
    unseen6,
    unseen7,
    unseen8,
    unseen9,
    unseen10,
    unseen11,
    unseen12,
)
from tools.perception.held_out.registry import builders, held_out, sets
from tools.perception.scene_base import Builder

__all__ = ["HELD_OUT_BUILDERS", "HELD_OUT_SETS", "held_out"]

HELD_OUT_BUILDERS: Dict[str, Builder] = builders()  # the held-out models' builders, by name
HELD_OUT_SETS: Dict[str, Dict[str, Tuple[str, ...]]] = sets()  # held-out split: its models by label, in order
