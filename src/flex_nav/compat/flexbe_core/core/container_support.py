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

:class:`FlexBEContainer` also carries what FlexBE code needs to drive a container itself (``sm.execute(userdata)``
one step at a time, ``sleep()``, ``spin()``, ``_userdata``, ``_last_exception``, locks, the process-wide
``OperatableStateMachine.autonomy_level`` while states are controlled): FlexBE 1.x's semantics, used by
flexbe_testing's Tester and FlexBE's own tests. A behavior run by flex_nav's executor never takes that path; the
sequential and concurrent steps are in :mod:`.operatable_state_machine` and :mod:`.concurrency_container`.

Two engine internals are written here and nowhere else, until the engine offers public setters:
the userdata defaults of a container (:func:`set_userdata_default`) and the input keys of a
sub-behavior's machine whose defaults must win (:func:`drop_input_keys`, FlexBE's ``default_keys``;
they are declared in the container's engine record, ``__flex_nav_runtime__``). Both happen while the
behavior is built, before it is validated and attached.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, Callable, Collection, Dict, Iterator, List, Mapping, Optional

from flex_nav.behavior.container import Container
from flex_nav.compat._construction import OpenedStack, construction_method
from flex_nav.compat.flexbe_core.core.exceptions import StateMachineError
from flex_nav.compat.flexbe_core.core.state import flexbe_path
from flex_nav.compat.flexbe_core.core.user_data import UserData
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
        from flex_nav.compat.flexbe_core.proxy import ProxyPublisher, ProxySubscriberCached  # noqa: PLC0415

        self.userdata = UserDataDefaults(self)  # type: ignore[arg-type]
        # FlexBE's direct execution (see the module docstring)
        self._userdata = UserData()
        self._flexbe_current: Any = None
        self._last_exception: Optional[BaseException] = None
        self._is_controlled = False
        self._locked = False
        self._inner_sync_request = False
        self._entering = True
        self.id: Any = None
        self._pub = ProxyPublisher()
        self._sub = ProxySubscriberCached()

    # --- FlexBE's view of the children ------------------------------------------------------------------
    @property
    def _states(self) -> List[Any]:
        return list(self._children.values())  # type: ignore[attr-defined]

    @property
    def _labels(self) -> Dict[str, Any]:
        return dict(self._children)  # type: ignore[attr-defined]

    @property
    def _remappings(self) -> Dict[str, Dict[str, str]]:
        return self._remapping  # type: ignore[attr-defined,no-any-return]

    def __contains__(self, label: object) -> bool:
        return label in self._children  # type: ignore[attr-defined]

    def __iter__(self) -> Iterator[str]:
        return iter(self._children)  # type: ignore[attr-defined]

    @property
    def path(self) -> str:
        attached = self.__flex_nav_runtime__.path  # type: ignore[attr-defined]
        return attached if attached else flexbe_path(self)

    @property
    def current_state(self) -> Any:
        """The active child: the engine's while flex_nav's executor runs the container, else FlexBE's (direct
        execution), which raises StateMachineError when no state is active, as in FlexBE."""
        rt = self.__flex_nav_runtime__  # type: ignore[attr-defined]
        if rt.ctx is not None and rt.active:
            current = getattr(self, "_current", None)
            return current.state if current is not None and current.active else None
        if self._flexbe_current is None:
            raise StateMachineError("No state active!")
        return self._flexbe_current

    @property
    def current_state_label(self) -> str:
        return str(self.current_state.name)

    @property
    def initial_state_label(self) -> str:
        states = self._states
        if not states:
            raise StateMachineError("No states added yet!")
        initial = getattr(self, "initial_state", None)
        return initial if isinstance(initial, str) else str(states[0].name)

    def get_deep_state(self) -> Any:
        """The innermost active state of a directly executed container (None when none is active)."""
        state = self._flexbe_current
        while isinstance(state, FlexBEContainer):
            state = state._flexbe_current
        return state

    # --- FlexBE's consistency check, locks and autonomy (direct execution) --------------------------------------
    def assert_consistent_transitions(self) -> None:
        """Every transition names a child or an outcome of this container (StateMachineError otherwise)."""
        valid = [*self._children, *self.outcomes]  # type: ignore[attr-defined]
        for transitions in self._flexbe_transitions().values():
            for target in transitions.values():
                if target not in valid:
                    raise StateMachineError(f"Transition target '{target}' missing in {valid}")

    def _flexbe_transitions(self) -> Dict[str, Mapping[str, str]]:
        """Child label -> {outcome: target} as given to ``add``."""
        return dict(getattr(self, "_transitions", {}))

    def transition_allowed(self, label: str, outcome: Optional[str]) -> bool:
        """False when ``outcome`` of child ``label`` would leave this container while it (or one above) is locked."""
        if outcome is None:
            return True
        target = self._flexbe_transitions().get(label, {}).get(outcome)
        if target is not None and target in self.outcomes:  # type: ignore[attr-defined]
            parent = self.parent  # type: ignore[attr-defined]
            if self._locked:
                return False
            if parent is not None and hasattr(parent, "transition_allowed"):
                return bool(parent.transition_allowed(self.name, target))  # type: ignore[attr-defined]
        return True

    def is_transition_allowed(self, label: str, outcome: Optional[str]) -> bool:
        """FlexBE: the outcome's required autonomy is below ``OperatableStateMachine.autonomy_level``."""
        levels = self._autonomy.get(label, {})  # type: ignore[attr-defined]
        return int(levels.get(outcome, -1)) < autonomy_level()

    def get_required_autonomy(self, outcome: str) -> int:
        return int(self._autonomy[self.current_state_label].get(outcome, 0))  # type: ignore[attr-defined]

    def lock(self, path: str) -> bool:
        if path == self.path:
            self._locked = True
            return True
        parent = self.parent  # type: ignore[attr-defined]
        return bool(parent is not None and hasattr(parent, "lock") and parent.lock(path))

    def unlock(self, path: str) -> bool:
        if path == self.path:
            self._locked = False
            return True
        parent = self.parent  # type: ignore[attr-defined]
        return bool(parent is not None and hasattr(parent, "unlock") and parent.unlock(path))

    def is_locked(self) -> bool:
        return self._locked

    # --- FlexBE's direct execution: shared steps ---------------------------------------------------------------
    def _flexbe_begin(self, userdata: Any) -> None:
        """First step of an activation: check the transitions, take the userdata, add the container's defaults."""
        self.assert_consistent_transitions()
        if userdata is not None:
            self._userdata = userdata if isinstance(userdata, UserData) else _wrap_mapping(userdata)
        for key, value in self._defaults.items():  # type: ignore[attr-defined]
            if key not in self._userdata._data:
                self._userdata._data[key] = value

    def _flexbe_view(self, state: Any) -> UserData:
        """The userdata view of child ``state`` on this container's data."""
        return UserData(
            reference=self._userdata,
            input_keys=state.input_keys,
            output_keys=state.output_keys,
            remap=self._remapping[state.name],  # type: ignore[attr-defined]
        )

    def _flexbe_guarded(self, step: Callable[[], Optional[str]]) -> Optional[str]:
        """Run one step; an exception is kept in ``_last_exception`` and logged, and the step gives None (FlexBE
        keeps the state active so that the operator can intervene)."""
        try:
            outcome = step()
        except Exception as err:
            from flex_nav.compat.flexbe_core.logger import Logger  # noqa: PLC0415

            self._last_exception = err
            label = self._flexbe_current.name if self._flexbe_current is not None else "?"
            Logger.logerr(f"Failed to execute state {label}:\n{err}")
            return None
        self._last_exception = None
        return outcome

    def spin(self, userdata: Any = None) -> Optional[str]:
        """Execute (and sleep in between) until an outcome."""
        outcome = self.execute(userdata)  # type: ignore[attr-defined]
        while outcome is None:
            self.sleep()
            outcome = self.execute(None)  # type: ignore[attr-defined]
        return outcome  # type: ignore[no-any-return]

    def sleep(self) -> None:
        """Wait until the active child is due again."""
        if self._flexbe_current is not None:
            self._flexbe_current.sleep()

    @property
    def sleep_duration(self) -> float:
        """[s] until the active child is due again (0 when none is active)."""
        return float(self._flexbe_current.sleep_duration) if self._flexbe_current is not None else 0.0

    def wait(self, seconds: Optional[float] = None, condition: Optional[Callable[[], bool]] = None) -> None:
        """Sleep ``seconds`` [s], or poll ``condition`` every 10 ms (bounded by ``seconds`` when both are given)."""
        deadline = time.monotonic() + seconds if seconds is not None else None
        if condition is None:
            if seconds is not None and seconds > 0:
                time.sleep(seconds)
            return
        while not condition():
            if deadline is not None and time.monotonic() >= deadline:
                return
            time.sleep(0.01)

    # --- FlexBE's "control" and lifecycle of a directly executed container ---------------------------------------
    def _enable_ros_control(self) -> None:
        self._is_controlled = True
        for state in self._states:
            if hasattr(state, "_enable_ros_control"):
                state._enable_ros_control()

    def _disable_ros_control(self) -> None:
        self._is_controlled = False
        for state in self._states:
            if hasattr(state, "_disable_ros_control"):
                state._disable_ros_control()

    def _notify_start(self) -> None:
        for state in self._states:
            if isinstance(state, FlexBEContainer):
                state._notify_start()
            else:
                state.on_start()

    def _notify_stop(self) -> None:
        for state in self._states:
            if isinstance(state, FlexBEContainer):
                state._notify_stop()
            else:
                state.on_stop()
            if getattr(state, "_is_controlled", False):
                state._disable_ros_control()

    def confirm(self, name: str, id: Any) -> None:
        """FlexBE: name the top-level machine and start its states (``on_start``) before the first execute."""
        if not self.name:  # type: ignore[attr-defined]
            self.__flex_nav_runtime__.label = name  # type: ignore[attr-defined]
        self.id = id
        if autonomy_level() != 255:
            self._enable_ros_control()
        self._notify_start()

    def destroy(self) -> None:
        """FlexBE: stop the states (``on_stop``) after the last execute."""
        self._notify_stop()
        self._disable_ros_control()

    def on_exit(self, userdata: Any) -> None:
        """Exit the active child of a directly executed container (``on_exit`` with its view)."""
        current = self._flexbe_current
        if current is not None:
            current._entering = True
            current.on_exit(self._flexbe_view(current))
            self._flexbe_current = None

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


def autonomy_level() -> int:
    """FlexBE's process-wide ``OperatableStateMachine.autonomy_level`` (direct execution only)."""
    from flex_nav.compat.flexbe_core.core.operatable_state_machine import OperatableStateMachine  # noqa: PLC0415

    return int(OperatableStateMachine.autonomy_level)


def _wrap_mapping(data: Any) -> UserData:
    store = UserData()
    for key in data:
        store[key] = data[key]
    return store


__all__ = ["FlexBEContainer", "UserDataDefaults", "Wiring", "autonomy_level", "drop_input_keys", "set_userdata_default"]
