"""SMACH's exception types (defined in :mod:`flex_nav.exceptions`, part of flex_nav's error family)."""

from flex_nav.exceptions import (
    InvalidConstructionError,
    InvalidStateError,
    InvalidTransitionError,
    InvalidUserCodeError,
    SmachError,
)

__all__ = [
    "InvalidConstructionError",
    "InvalidStateError",
    "InvalidTransitionError",
    "InvalidUserCodeError",
    "SmachError",
]
