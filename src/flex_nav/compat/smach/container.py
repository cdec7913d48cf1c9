"""SMACH's container base: userdata, callbacks, construction (``with sm:``) and the introspection interface.

What every container offers (and smach_ros's IntrospectionServer and ActionServerWrapper use):
``get_children()``, ``__getitem__(label)``, ``get_initial_states()``, ``set_initial_state(states,
userdata)``, ``get_active_states()``, ``get_internal_edges()`` (``(outcome, from, to)`` triples),
``check_consistency()``, ``is_running()``, ``userdata`` (a :class:`UserData` whose dict is ``_data``),
and start / transition / termination callbacks::

    start_cb(userdata, initial_states, *cb_args)
    transition_cb(userdata, active_states, *cb_args)
    termination_cb(userdata, terminal_states, container_outcome, *cb_args)

A callback that raises fails the container with :class:`InvalidUserCodeError` (SMACH only logs it).

Construction: ``with container:`` (or ``with container.opened():``) opens it; class-level calls
such as ``StateMachine.add(...)`` act on the innermost opened container of the current thread. On
leaving the block the container is checked (``check_consistency``) and problems are logged, as in
SMACH (it may be opened again to add the missing states); ``execute`` checks again and raises.
Input keys are copied in from the parent's userdata when a container starts, output keys back out
when it finishes.
"""

from __future__ import annotations

import threading
from typing import Any, Callable, Collection, Dict, List, Mapping, Optional, Sequence, Tuple

from flex_nav.compat._construction import OpenedStack, construction_method
from flex_nav.compat.smach._hooks import HOOKS
from flex_nav.compat.smach.state import State
from flex_nav.compat.smach.user_data import UserData
from flex_nav.exceptions import InvalidStateError, InvalidTransitionError, InvalidUserCodeError, SmachError

_OPENED: OpenedStack[Container] = OpenedStack("flex_nav_smach_opened_containers")

Callback = Tuple[Callable[..., Any], Tuple[Any, ...]]

SMACH_ERRORS = (SmachError,)  # raised by containers: passed through unchanged by enclosing containers


def _opened_container(cls: type) -> Container:
    opened = _OPENED.top()
    if opened is None:
        raise InvalidStateError(
            f"{cls.__name__}: no container is opened; open one with 'with container:' before adding states"
        )
    if not isinstance(opened, cls):
        raise InvalidStateError(
            f"calling a {cls.__name__} construction method, but the opened container is a {type(opened).__name__}"
        )
    return opened


def smach_construction(func: Callable[..., Any]) -> construction_method:
    """Mark a container method as a SMACH construction method (``Class.add`` acts on the opened container)."""
    return construction_method(func, _opened_container, lambda: _OPENED.top() is not None)


class Container(State):
    """Base class of SMACH containers (StateMachine, Concurrence, Iterator, ...)."""

    def __init__(
        self,
        outcomes: Sequence[str] = (),
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
    ) -> None:
        super().__init__(outcomes, input_keys, output_keys)
        self.userdata = UserData()
        self._start_cbs: List[Callback] = []
        self._transition_cbs: List[Callback] = []
        self._termination_cbs: List[Callback] = []
        self._is_running = False
        self._cb_lock = threading.RLock()  # callbacks of one container never run at the same time

    # --- interface the containers implement -----------------------------------------------------------
    def __getitem__(self, key: str) -> State:
        raise NotImplementedError

    def get_children(self) -> Dict[str, State]:
        """Children by label (a new dict)."""
        raise NotImplementedError

    def set_initial_state(self, initial_states: Sequence[str], userdata: Optional[UserData] = None) -> None:
        raise NotImplementedError

    def get_initial_states(self) -> List[str]:
        raise NotImplementedError

    def get_active_states(self) -> List[str]:
        raise NotImplementedError

    def get_internal_edges(self) -> List[Tuple[str, str, Optional[str]]]:
        raise NotImplementedError

    def check_consistency(self) -> None:
        raise NotImplementedError

    def is_running(self) -> bool:
        return self._is_running

    def _start_running(self, this: str) -> None:
        """Mark the container running; InvalidStateError naming ``this`` container if it already is."""
        if self._is_running:
            raise InvalidStateError(f"{this} is already running (execute is not re-entrant)")
        self._is_running = True

    # --- userdata passing ----------------------------------------------------------------------------------
    def _copy_input_keys(self, parent_ud: Any, ud: UserData) -> None:
        if parent_ud is None:
            return
        for key in self.get_registered_input_keys():
            if key in parent_ud:
                ud[key] = parent_ud[key]
            else:
                HOOKS.warn(f"copying input key {key!r} into the container, but the parent userdata has no value for it")

    def _copy_output_keys(self, ud: UserData, parent_ud: Any) -> None:
        if parent_ud is None:
            return
        for key in self.get_registered_output_keys():
            if key in ud:
                parent_ud[key] = ud[key]
            else:
                HOOKS.warn(f"copying output key {key!r} out of the container, but it has no value")

    # --- callbacks ---------------------------------------------------------------------------------------------
    def register_start_cb(self, start_cb: Callable[..., Any], cb_args: Sequence[Any] = ()) -> None:
        """``start_cb(userdata, initial_states, *cb_args)`` when the container starts."""
        self._start_cbs.append((self._callable(start_cb, "start"), tuple(cb_args)))

    def register_transition_cb(self, transition_cb: Callable[..., Any], cb_args: Sequence[Any] = ()) -> None:
        """``transition_cb(userdata, active_states, *cb_args)`` when the active states change."""
        self._transition_cbs.append((self._callable(transition_cb, "transition"), tuple(cb_args)))

    def register_termination_cb(self, termination_cb: Callable[..., Any], cb_args: Sequence[Any] = ()) -> None:
        """``termination_cb(userdata, terminal_states, container_outcome, *cb_args)`` when it finishes."""
        self._termination_cbs.append((self._callable(termination_cb, "termination"), tuple(cb_args)))

    @staticmethod
    def _callable(cb: Callable[..., Any], what: str) -> Callable[..., Any]:
        if not callable(cb):
            raise InvalidStateError(f"{what} callback must be callable, got {cb!r}")
        return cb

    def _run_cbs(self, what: str, cbs: List[Callback], *args: Any) -> None:
        with self._cb_lock:
            for cb, cb_args in cbs:
                try:
                    cb(self.userdata, *args, *cb_args)
                except Exception as err:
                    raise InvalidUserCodeError(
                        f"{what} callback {getattr(cb, '__name__', cb)!r} of {type(self).__name__} raised "
                        f"{type(err).__name__}: {err}"
                    ) from err

    def call_start_cbs(self) -> None:
        if self._start_cbs:
            self._run_cbs("start", self._start_cbs, self.get_initial_states())

    def call_transition_cbs(self) -> None:
        if self._transition_cbs:
            self._run_cbs("transition", self._transition_cbs, self.get_active_states())

    def call_termination_cbs(self, terminal_states: Collection[str], outcome: Optional[str]) -> None:
        if self._termination_cbs:
            self._run_cbs("termination", self._termination_cbs, list(terminal_states), outcome)

    # --- construction ------------------------------------------------------------------------------------------
    def __enter__(self) -> Container:
        self.open()
        return self

    def __exit__(self, exc_type: Optional[type], exc: Optional[BaseException], tb: Any) -> None:
        if exc_type is None:
            self.close()
        else:
            _OPENED.pop(self)  # leave the stack clean; the error propagates

    def opened(self, **kwargs: Any) -> _OpenedContext:
        """``with container.opened():`` -- the same as ``with container:`` (SMACH ignores the keyword arguments too)."""
        return _OpenedContext(self)

    def open(self) -> None:
        """Open this container for construction (class-level construction calls now act on it)."""
        _OPENED.push(self)

    def close(self) -> None:
        """Close this container (it must be the innermost opened one) and log consistency problems."""
        if not _OPENED.pop(self):
            raise InvalidStateError(f"closing a {type(self).__name__} that is not the innermost opened container")
        try:
            self.check_consistency()
        except (InvalidStateError, InvalidTransitionError) as err:
            HOOKS.error(f"container consistency check failed (execute will refuse to run it): {err}")

    def is_opened(self) -> bool:
        return _OPENED.top() is self

    def assert_opened(self, msg: str = "") -> None:
        if not self.is_opened():
            raise InvalidStateError(msg or f"this {type(self).__name__} is not opened for construction")

    @staticmethod
    def _any_containers_opened() -> bool:
        return _OPENED.top() is not None

    @classmethod
    def _currently_opened_container(cls) -> Container:
        return _opened_container(cls)


class _OpenedContext:
    def __init__(self, container: Container) -> None:
        self._container = container

    def __enter__(self) -> Container:
        self._container.open()
        return self._container

    def __exit__(self, exc_type: Optional[type], exc: Optional[BaseException], tb: Any) -> None:
        self._container.__exit__(exc_type, exc, tb)


def run_child(label: str, state: Any, ud: Any) -> Any:
    """Execute a child state; anything but a SMACH error becomes InvalidUserCodeError naming the child."""
    try:
        return state.execute(ud)
    except SMACH_ERRORS:
        raise
    except Exception as err:
        raise InvalidUserCodeError(
            f"state {label!r} ({type(state).__name__}) raised {type(err).__name__}: {err}"
        ) from err


def check_state_interface(label: object, state: object, container: str) -> str:
    """The label, after checking it is a name and ``state`` looks like a SMACH state."""
    if not isinstance(label, str) or not label:
        raise InvalidStateError(f"{container}: state label must be a non-empty string, got {label!r}")
    if not (callable(getattr(state, "execute", None)) and hasattr(state, "get_registered_outcomes")):
        raise InvalidStateError(
            f"{container}: {label!r} must be a SMACH state (execute(ud) and get_registered_outcomes()), "
            f"got {type(state).__name__}"
        )
    return label


def labelled_child(children: Mapping[str, Any], key: str, missing: str, labels: str) -> Any:
    """The child labelled ``key``; a KeyError saying ``missing`` and listing the ``labels`` otherwise."""
    try:
        return children[key]
    except KeyError:
        raise KeyError(f"{missing} {key!r} ({labels}: {listed(list(children))})") from None


def listed(values: Sequence[Any]) -> str:
    """``values`` for a message: comma-separated, or ``none``."""
    return ", ".join(str(v) for v in values) if values else "none"


__all__ = ["Container"]
