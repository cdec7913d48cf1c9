"""The typed exceptions of flex_nav.

Every error flex_nav raises on purpose derives from :class:`FlexNavError`, so a caller can catch
the family, and each subclass says what kind of failure it is. Messages name the bad value and,
where there is a fixed set, the valid choices (see :func:`choices_message`). Causes are chained
with ``raise ... from err``.
"""

from __future__ import annotations

from collections.abc import Iterable


class FlexNavError(Exception):
    """Base class of all flex_nav errors."""


class ConfigError(FlexNavError, ValueError):
    """A parameter, file or argument has a bad value (found when loading or constructing)."""


class NotReadyError(FlexNavError):
    """Something needed is not there yet (no master, no server, no message, no transform)."""


class TimedOutError(FlexNavError):
    """A bounded wait ran out."""


class InstallError(FlexNavError):
    """The installation is incomplete (e.g. the action classes were not generated)."""


class MappingError(FlexNavError):
    """The mapper cannot build its map: the pose graph cannot be optimized (a node no chain of edges ties to the
    first, or the solver failed; flex_nav.mapping.pose_graph)."""


def choices_message(what: str, bad: object, valid: Iterable[object]) -> str:
    """Format ``"<what> 'bad' is not valid (valid: a, b, c)"`` with the choices sorted as given."""
    listed = ", ".join(repr(v) if not isinstance(v, str) else v for v in valid)
    return f"{what} {bad!r} is not valid (valid: {listed or 'none'})"


# --- behavior engine (flex_nav.behavior) --------------------------------------------------------


class BehaviorError(FlexNavError):
    """Base class of the behavior engine's errors (construction, loading, userdata, runtime, commands)."""


class BehaviorConstructionError(BehaviorError, ConfigError):
    """A behavior is built wrong; found when a state is added or when the machine is validated.

    ``container`` is the path of the container at fault (``"/"`` for the root), ``label`` the state
    label inside it (or None), ``item`` the bad outcome/target/key (or None) and ``field`` what the item
    is (``"transition"``, ``"autonomy"``, ``"remapping"``, ``"initial"``, ``"condition"``, ``"key"``,
    ``"label"``, ``"state"``) so that a loader can point at the line that defines it.
    """

    def __init__(
        self, message: str, container: str = "", label: str | None = None, item: object = None, field: str = ""
    ) -> None:
        super().__init__(message)
        self.container = container
        self.label = label
        self.item = item
        self.field = field


class UnknownTargetError(BehaviorConstructionError):
    """A transition goes to a label that is neither a state of the container nor one of its outcomes."""


class UnregisteredOutcomeError(BehaviorConstructionError):
    """A transition, autonomy level or condition names an outcome the state does not register."""


class MissingTransitionError(BehaviorConstructionError):
    """A registered outcome of a state has no transition."""


class UnreachableStateError(BehaviorConstructionError):
    """A state cannot be reached from the initial state."""


class LabelClashError(BehaviorConstructionError):
    """A state label is used twice, is malformed, or equals an outcome of its container."""


class MissingInitialStateError(BehaviorConstructionError):
    """A state machine has no states, or its initial state is not one of them."""


class UndeclaredKeyError(BehaviorConstructionError):
    """A userdata key is used (remapping, input, output) that nobody declares or provides."""


class BehaviorLoadError(BehaviorConstructionError):
    """A behavior definition file is wrong; the message reads ``file:line: what is wrong (valid: ...)``."""

    def __init__(self, message: str, file: str = "", line: int = 0) -> None:
        super().__init__(f"{file}:{line}: {message}" if file else message, field="file")
        self.file = file
        self.line = line
        self.reason = message


class BehaviorLoadLimitError(BehaviorLoadError):
    """A load crossed one of its bounds (:class:`flex_nav.behavior.yaml_limits.LoadLimits`): ``limit`` is the
    limit's name (e.g. ``"max_yaml_nodes"``) and ``value`` its value; the message names both."""

    def __init__(self, message: str, limit: str, value: float, file: str = "", line: int = 0) -> None:
        super().__init__(message, file, line)
        self.limit = limit
        self.value = value


class UserDataError(BehaviorError):
    """A state used userdata against its declaration while running."""


class UserDataKeyError(UserDataError, KeyError, AttributeError):
    """Read or write of an undeclared userdata key, or read of a key that has no value yet."""

    def __str__(self) -> str:  # KeyError would repr() the message
        return str(self.args[0]) if self.args else ""


class ReadOnlyUserDataError(UserDataError, TypeError):
    """Write to an input-only userdata key, or mutation through a read-only view of its value."""


class BehaviorRuntimeError(BehaviorError):
    """A running behavior broke its contract (e.g. a state returned an unregistered outcome)."""


class BehaviorCommandError(BehaviorError, ValueError):
    """An operator command cannot be applied (unknown path, outcome not registered, nothing requested)."""


# --- SMACH compatibility (flex_nav.compat.smach re-exports these under SMACH's names) ---------------


class SmachError(BehaviorError):
    """Base of SMACH's four exception types (SMACH derives them from Exception; here they join the family)."""


class InvalidStateError(SmachError, BehaviorConstructionError):
    """SMACH: a state or container is used wrongly (duplicate label, bad outcome policy, nothing opened)."""


class InvalidTransitionError(SmachError, BehaviorConstructionError):
    """SMACH: a transition names an unknown target or outcome, or a state returned an unregistered outcome."""


class InvalidConstructionError(SmachError, BehaviorConstructionError):
    """SMACH: a container was modified while it was not opened for construction."""


class InvalidUserCodeError(SmachError, BehaviorRuntimeError):
    """SMACH: user code (a state's execute, a callback) raised, or read/wrote undeclared userdata."""


# --- FlexBE compatibility (flex_nav.compat.flexbe_core.core.exceptions re-exports these under FlexBE's names) ---


class FlexBEError(BehaviorError):
    """Base of FlexBE's three exception types (FlexBE derives them from Exception; here they join the family)."""


class FlexBEStateError(FlexBEError):
    """FlexBE's ``StateError``: a state returned an outcome without a transition, or was renamed or re-parented."""


class FlexBEStateMachineError(FlexBEError):
    """FlexBE's ``StateMachineError``: a container is built wrong (a transition to an unknown target, a duplicate
    label, nothing opened) or asked for a state while none is active."""


class FlexBEUserDataError(FlexBEError, UserDataError):
    """FlexBE's ``UserDataError``: a state read a key it does not declare as input, wrote one it does not declare
    as output, read a key that has no value, or modified an input-only value."""
