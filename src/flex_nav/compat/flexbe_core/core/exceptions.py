"""flexbe_core.core.exceptions: FlexBE's exception types (defined in :mod:`flex_nav.exceptions`, part of flex_nav's
error family; ``except StateError`` in FlexBE code catches them as in FlexBE)."""

from flex_nav.exceptions import FlexBEStateError as StateError
from flex_nav.exceptions import FlexBEStateMachineError as StateMachineError
from flex_nav.exceptions import FlexBEUserDataError as UserDataError

__all__ = ["StateError", "StateMachineError", "UserDataError"]
