"""What FlexBE's containers share: ``with sm:``, the class-level ``add``, and ``sm.userdata`` defaults.

Generated FlexBE behaviors build containers like this::

    _state_machine = OperatableStateMachine(outcomes=['finished', 'failed'])
    _state_machine.userdata.speed = 0.2            # a userdata default
    with _state_machine:
        OperatableStateMachine.add('Wait', WaitState(wait_time=1), transitions={'done': 'finished'},
                                   autonomy={'done': Autonomy.Off}, remapping={})

``OperatableStateMachine.add`` acts on the innermost container opened in the current thread (whatever
its kind: generated code also adds the children of a ConcurrencyContainer this way); called on an
instance with nothing opened it acts on that instance. ``userdata`` here is the container's userdata
*defaults* (what FlexBE's generated code sets); the values a running state sees are in its own
userdata view.

Two engine internals are written here and nowhere else, until the engine offers public setters:
the userdata defaults of a container (:func:`set_userdata_default`) and the input keys of a
sub-behavior's machine whose defaults must win (:func:`drop_input_keys`, FlexBE's ``default_keys``;
they are declared in the container's engine record, ``__flex_nav_runtime__``). Both happen while the
behavior is built, before it is validated and attached.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Collection, Iterator, List, Mapping, Optional

from flex_nav.behavior.container import Container
from flex_nav.compat._construction import OpenedStack, construction_method
from flex_nav.exceptions import BehaviorConstructionError, ConfigError, UserDataKeyError

_OPENED: OpenedStack[Any] = OpenedStack("flex_nav_flexbe_opened_containers")


def set_userdata_default(container: Container, key: str, value: Any) -> None:
    """Give ``key`` the default ``value`` in ``container`` (before the behavior runs)."""
    if not isinstance(key, str) or not key or key.startswith("_"):
        raise ConfigError(f"userdata key {key!r} must be a name that does not start with '_'")
    container._defaults[key] = value


def drop_input_keys(container: Container, keys: Collection[str]) -> None:
    """Stop taking ``keys`` from the parent: the container's own defaults are used instead."""
    unknown = [k for k in keys if k not in container.input_keys]
    if unknown:
        raise ConfigError(
            f"default_keys {unknown} are not input keys of the sub-behavior (input keys: "
            f"{', '.join(container.input_keys) or 'none'})"
        )
    container.__flex_nav_runtime__.input_keys = tuple(k for k in container.input_keys if k not in keys)


class UserDataDefaults:
    """``container.userdata`` of a FlexBE container: its userdata defaults, by attribute or item."""

    __slots__ = ("_owner",)

    def __init__(self, owner: Container) -> None:
        object.__setattr__(self, "_owner", owner)

    def __getattr__(self, key: str) -> Any:
        if key.startswith("_"):
            raise AttributeError(key)
        return self[key]

    def __setattr__(self, key: str, value: Any) -> None:
        set_userdata_default(self._owner, key, value)

    def __getitem__(self, key: str) -> Any:
        defaults = self._owner.userdata_defaults
        try:
            return defaults[key]
        except KeyError:
            raise UserDataKeyError(
                f"userdata of {type(self._owner).__name__} has no default {key!r} "
                f"(defaults: {', '.join(sorted(defaults)) or 'none'})"
            ) from None

    def __setitem__(self, key: str, value: Any) -> None:
        set_userdata_default(self._owner, key, value)

    def __contains__(self, key: object) -> bool:
        return key in self._owner.userdata_defaults

    def __iter__(self) -> Iterator[str]:
        return iter(self._owner.userdata_defaults)

    def keys(self) -> List[str]:
        return list(self._owner.userdata_defaults)

    def __repr__(self) -> str:
        return f"<userdata defaults {self._owner.userdata_defaults!r}>"


@dataclass(frozen=True)
class Wiring:
    """What FlexBE's ``add`` gives with a child besides its label: where its outcomes go, their autonomy levels
    and its userdata remapping (each None when not given)."""

    transitions: Optional[Mapping[str, str]] = None
    autonomy: Optional[Mapping[str, object]] = None
    remapping: Optional[Mapping[str, str]] = None


def _opened(cls: type) -> Any:
    top = _OPENED.top()
    if top is None:
        raise BehaviorConstructionError(
            f"{cls.__name__}.add: no container is opened; add states inside 'with container:'", field="state"
        )
    return top


def _add(  # noqa: PLR0917  (FlexBE's signature of add)
    target: Any,
    label: str,
    state: Any,
    transitions: Optional[Mapping[str, str]] = None,
    autonomy: Optional[Mapping[str, object]] = None,
    remapping: Optional[Mapping[str, str]] = None,
) -> Any:
    return target._flexbe_add(label, state, Wiring(transitions, autonomy, remapping))


class FlexBEContainer:
    """Mixin giving an engine container FlexBE's construction idiom (put it first among the bases)."""

    add = construction_method(_add, _opened, lambda: _OPENED.top() is not None)

    def _init_flexbe(self) -> None:
        self.userdata = UserDataDefaults(self)  # type: ignore[arg-type]

    def __enter__(self) -> Any:
        _OPENED.push(self)
        return self

    def __exit__(self, exc_type: Optional[type], exc: Optional[BaseException], tb: Any) -> None:
        popped = _OPENED.pop(self)
        if exc_type is None and not popped:
            raise BehaviorConstructionError(
                f"closing a {type(self).__name__} that is not the innermost opened container", field="state"
            )

    def _flexbe_add(self, label: str, state: Any, wiring: Wiring) -> Any:
        """Add ``state`` as ``label`` with its ``wiring``, the way this kind of container adds a child."""
        raise NotImplementedError


__all__ = ["FlexBEContainer", "UserDataDefaults", "Wiring", "drop_input_keys", "set_userdata_default"]
