"""The held-out sets' registry: ``@held_out(split, label, model)`` on a builder files it as the model ``model`` of
``label`` in the held-out split ``split``.

:mod:`tools.perception.held_out` reads the tables once every set's module is imported: a split's models of a label
in the order their builders were registered (the order :func:`tools.perception.scenes.plan` cycles through them, so
the order of the definitions in a set's module is part of its renders), the splits in the order of their number
(``unseen``, ``unseen2``, .., ``unseen12``: the order they were defined in).
"""

from __future__ import annotations

import re
from typing import Callable, Dict, List, Tuple, TypeVar

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.perception.labels import LABELS
from tools.perception.scene_base import Builder

B = TypeVar("B", bound=Builder)
SPLIT_NAME = re.compile(r"unseen([2-9]|[1-9][0-9]+)?")  # 'unseen' is the first set, then 'unseen2', 'unseen3', ..

_MODELS: Dict[str, Dict[str, List[str]]] = {}  # split: label: model names, in the order registered
_BUILDERS: Dict[str, Builder] = {}  # model name: builder, over all the splits


def held_out(split: str, label: str, model: str) -> Callable[[B], B]:
    """Register the decorated builder as the held-out model ``model`` (a name no other held-out model has) of
    ``label`` (one of :data:`flex_nav.perception.labels.LABELS`) in ``split`` (``unseen``, ``unseen2``, ..): it
    joins the end of the split's models of that label."""
    if SPLIT_NAME.fullmatch(split) is None:
        raise ConfigError(f"held-out model {model!r}: the split {split!r} is not named 'unseen', 'unseen2', "
                          "'unseen3', ..")
    if label not in LABELS:
        raise ConfigError(f"held-out model {model!r}: " + choices_message("label", label, LABELS))

    def register(builder: B) -> B:
        if model in _BUILDERS:
            raise ConfigError(f"held-out model {model!r} is already registered; give the one in {split!r} another name")
        _MODELS.setdefault(split, {name: [] for name in LABELS})[label].append(model)
        _BUILDERS[model] = builder
        return builder

    return register


def builders() -> Dict[str, Builder]:
    """Every registered held-out model's builder, by name (a copy)."""
    return dict(_BUILDERS)


def sets() -> Dict[str, Dict[str, Tuple[str, ...]]]:
    """Every registered split's models by label (the labels in the order of ``LABELS``, the models in the order
    registered), the splits in the order of their number. A split without a model of some label stops it."""
    for split, models in _MODELS.items():
        missing = [label for label, names in models.items() if not names]
        if missing:
            raise ConfigError(f"held-out split {split!r} has no model of {missing}; it has {models}")
    ordered = sorted(_MODELS, key=_number)
    return {split: {label: tuple(names) for label, names in _MODELS[split].items()} for split in ordered}


def _number(split: str) -> int:
    match = SPLIT_NAME.fullmatch(split)
    assert match is not None  # checked when registered
    return int(match.group(1) or 1)
