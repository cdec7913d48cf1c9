"""The labels the obstacle classifier reports and the roles a detector's class names map to.

``person`` and ``movable`` are what the push-or-avoid behavior acts on; ``clear`` means neither is in
the region of interest (empty floor, walls and fixed furniture are all ``clear``); ``unknown`` is
reported by the temporal vote while no label has a majority yet.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Optional, Sequence, Tuple

from flex_nav.exceptions import ConfigError, choices_message

PERSON = "person"
MOVABLE = "movable"
CLEAR = "clear"
UNKNOWN = "unknown"

LABELS: Tuple[str, ...] = (PERSON, MOVABLE, CLEAR)  # what one frame can be classified as
VOTE_LABELS: Tuple[str, ...] = (*LABELS, UNKNOWN)  # what the temporal vote can report

IGNORE = "ignore"
ROLES: Tuple[str, ...] = (PERSON, MOVABLE, IGNORE)  # what a detector class name may be mapped to


@dataclass(frozen=True)
class Prediction:
    """What one frame shows in the region of interest: a label of :data:`LABELS` and its confidence [0..1].

    ``scores`` holds the per-label score the decision was made from (classifier: summed class
    probabilities; detector: best detection score per label in the region, ``clear`` = 1 - the best).
    """

    label: str
    confidence: float
    scores: Mapping[str, float] = field(default_factory=dict)


def label_of_role(role: str) -> str:
    """The frame label a detector role stands for (``ignore`` -> ``clear``)."""
    return CLEAR if role == IGNORE else role


def class_roles(class_names: Sequence[str], class_map: Optional[Mapping[str, str]], what: str) -> Tuple[str, ...]:
    """The role (:data:`ROLES`) of every model class, in class order.

    ``class_map`` maps model class names to ``person``, ``movable`` or ``ignore``; a class it does not
    name is ``ignore`` unless the class is itself called ``person`` or ``movable``. With no map the same
    default applies to every class. A key that is not a class name, or a value that is not a role,
    raises ConfigError naming ``what``, the bad entry and the valid choices.
    """
    given = dict(class_map or {})
    for name, role in given.items():
        if name not in class_names:
            raise ConfigError(choices_message(f"{what}: class", name, class_names))
        if role not in ROLES and role != CLEAR:
            raise ConfigError(choices_message(f"{what}[{name!r}]: role", role, ROLES))
    roles = []
    for name in class_names:
        role = given.get(name, name if name in (PERSON, MOVABLE) else IGNORE)
        roles.append(IGNORE if role == CLEAR else role)
    return tuple(roles)
