"""SMACH's StateMachine: one state at a time, transitions by outcome, blocking ``execute``.

::

    sm = smach.StateMachine(outcomes=["outcome4"])
    with sm:
        smach.StateMachine.add("FOO", Foo(), transitions={"outcome1": "BAR", "outcome2": "outcome4"})
        smach.StateMachine.add("BAR", Bar(), transitions={"outcome1": "FOO"})
    outcome = sm.execute()

Transitions map each outcome of a state to another state's label or to an outcome of the machine.
An outcome left out (or mapped to ``None``) falls through: the machine finishes with the outcome of
the same name, which must then be one of its outcomes. The first state added is the initial state
unless ``set_initial_state`` says otherwise. ``add_auto`` connects the given outcomes of a state to
the state added next. ``set_initial_state`` may name a state that is added later (checked at ``execute``).

Preemption (as in SMACH): ``request_preempt()`` sets the machine's flag and forwards the request to the
running state. When that state returns, the machine checks whether it serviced the request
(``service_preempt()``): if so, the request counts as handled and the machine follows the returned
outcome (typically ``'preempted'`` -> the machine's ``'preempted'``); if not, the next state is
preempted before it runs. A request made before ``execute`` preempts the initial state.

Failure is loud: an inconsistent machine raises :class:`InvalidTransitionError` from ``execute`` (SMACH
logs and returns None); a state that raises makes ``execute`` raise :class:`InvalidUserCodeError`
(chained to the original); a returned outcome that is not registered raises
:class:`InvalidTransitionError` naming the registered ones. With a shutdown check set
(``set_shutdown_check``), the machine preempts the running state and returns ``'preempted'`` (if it
has that outcome; None otherwise) when shutdown is detected between states.
"""

from __future__ import annotations

import threading
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

from flex_nav.compat.smach._hooks import HOOKS
from flex_nav.compat.smach.container import (
    Container,
    check_state_interface,
    labelled_child,
    listed,
    run_child,
    smach_construction,
)
from flex_nav.compat.smach.user_data import Remapper, UserData, remapping_of
from flex_nav.compat.smach.util import is_shutdown, names
from flex_nav.exceptions import InvalidStateError, InvalidTransitionError

_UNBOUND = object()


class StateMachine(Container):
    """A SMACH finite state machine (also a state, so machines nest)."""

    def __init__(
        self, outcomes: Sequence[str], input_keys: Sequence[str] = (), output_keys: Sequence[str] = ()
    ) -> None:
        super().__init__(outcomes, input_keys, output_keys)
        self._states: Dict[str, Any] = {}
        self._transitions: Dict[str, Dict[str, Optional[str]]] = {}
        self._remappings: Dict[str, Dict[str, str]] = {}
        self._initial_state_label: Optional[str] = None
        self._current_label: Optional[str] = None
        self._current_state: Any = None
        self._current_transitions: Optional[Dict[str, Optional[str]]] = None
        self._preempted_label: Optional[str] = None
        self._preempted_state: Any = None
        self._last_added_label: Optional[str] = None
        self._connector_outcomes: List[str] = []
        self._state_transitioning_lock = threading.RLock()  # held except while a child executes

    # --- construction ---------------------------------------------------------------------------------------
    def _add(
        self,
        label: str,
        state: Any,
        transitions: Optional[Mapping[str, Optional[str]]] = None,
        remapping: Optional[Mapping[str, str]] = None,
    ) -> Any:
        where = f"state machine {type(self).__name__}"
        label = check_state_interface(label, state, where)
        if label in self._states:
            raise InvalidStateError(
                f"{where}: state label {label!r} is already used (labels: {listed(list(self._states))})"
            )
        if label in self._outcomes:
            raise InvalidStateError(
                f"{where}: state label {label!r} is also an outcome of the machine "
                f"(outcomes: {listed(self.get_registered_outcomes())}); rename one"
            )
        bound = dict(transitions or {})
        self.check_state_spec(label, state, bound)
        for outcome in state.get_registered_outcomes():
            bound.setdefault(outcome, None)  # unbound: falls through to the machine outcome of that name
        if self._initial_state_label is None:
            self._initial_state_label = label
        self._states[label] = state
        self._transitions[label] = bound
        self._remappings[label] = remapping_of(remapping, f"{where} {label!r}")
        if self._connector_outcomes and self._last_added_label is not None:
            for outcome in self._connector_outcomes:
                self._transitions[self._last_added_label][outcome] = label
            self._connector_outcomes = []
            self._last_added_label = None
        return state

    def _add_auto(
        self,
        label: str,
        state: Any,
        connector_outcomes: Sequence[str],
        transitions: Optional[Mapping[str, Optional[str]]] = None,
        remapping: Optional[Mapping[str, str]] = None,
    ) -> Any:
        connectors = names("connector_outcomes", connector_outcomes, f"add_auto {label!r}")
        if hasattr(state, "get_registered_outcomes"):
            registered = state.get_registered_outcomes()
            missing = [o for o in connectors if o not in registered]
            if missing:
                raise InvalidStateError(
                    f"add_auto {label!r}: connector outcomes {listed(missing)} are not registered by the state "
                    f"(registered: {listed(registered)})"
                )
        added = StateMachine._add(self, label, state, transitions, remapping)
        self._last_added_label = label
        self._connector_outcomes = [o for o in connectors if (transitions or {}).get(o) is None]
        return added

    add = smach_construction(_add)
    add_auto = smach_construction(_add_auto)

    def check_state_spec(self, label: str, state: Any, transitions: Mapping[str, Any]) -> None:
        """Every outcome named in ``transitions`` must be registered by ``state`` (InvalidTransitionError)."""
        registered = state.get_registered_outcomes()
        for outcome, target in transitions.items():
            if outcome not in registered:
                raise InvalidTransitionError(
                    f"transition of state {label!r} names outcome {outcome!r}, which it does not register "
                    f"(registered: {listed(registered)})"
                )
            if target is not None and (not isinstance(target, str)):
                raise InvalidTransitionError(
                    f"transition {label!r}.{outcome} goes to {target!r}: not a state label or outcome name"
                )

    # --- introspection ------------------------------------------------------------------------------------------
    def get_children(self) -> Dict[str, Any]:
        return dict(self._states)

    def __getitem__(self, key: str) -> Any:
        return labelled_child(self._states, key, "state machine has no state", "states")

    def set_initial_state(self, initial_states: Sequence[str], userdata: Optional[UserData] = None) -> None:
        """Start at ``initial_states[0]`` next time; merge ``userdata`` into the machine's userdata.

        As in SMACH, the label is checked when the machine runs, not here: it may name a state added later
        (a label that is still unknown is logged as a warning; ``execute`` raises InvalidTransitionError if it
        is unknown then). More than one label: a warning, and the first one is taken.
        """
        states = [initial_states] if isinstance(initial_states, str) else list(initial_states)
        if len(states) > 1:
            HOOKS.warn(f"a StateMachine has exactly one initial state, got {states}: taking {states[0]!r}")
        if states:
            self._initial_state_label = states[0]
        if userdata is not None:
            self.userdata.update(userdata)
        if self._initial_state_label is not None and self._initial_state_label not in self._states:
            HOOKS.warn(
                f"initial state {self._initial_state_label!r} is not a state of the machine yet "
                f"(states: {listed(list(self._states))}); it must be added before the machine runs"
            )
        elif not self._is_running:
            self.call_start_cbs()  # introspection tools learn about the new initial state

    def get_active_states(self) -> List[str]:
        label = self._current_label
        return [label] if label is not None else []

    def get_initial_states(self) -> List[str]:
        return [self._initial_state_label] if self._initial_state_label is not None else []

    def get_internal_edges(self) -> List[Tuple[str, str, Optional[str]]]:
        return [
            (outcome, label, target)
            for label, transitions in self._transitions.items()
            for outcome, target in transitions.items()
        ]

    def check_consistency(self) -> None:
        """Raise InvalidTransitionError listing every problem: initial state, unknown targets, unregistered outcomes."""
        outcomes = self.get_registered_outcomes()
        available = [*self._states, *outcomes]
        errors: List[str] = []
        if self._initial_state_label is None:
            errors.append("no initial state (no state was added)")
        elif self._initial_state_label not in self._states:
            errors.append(f"initial state {self._initial_state_label!r} is not in the state machine")
        for label, transitions in self._transitions.items():
            for outcome, target in transitions.items():
                if target is None or target == "":
                    if outcome not in outcomes:
                        errors.append(
                            f"state {label!r}: outcome {outcome!r} has no transition and is not an outcome of the "
                            "machine to fall through to"
                        )
                elif target not in self._states and target not in outcomes:
                    errors.append(f"state {label!r}: transition {outcome!r} goes to unknown target {target!r}")
        if errors:
            raise InvalidTransitionError(
                f"state machine failed consistency check: {'; '.join(errors)} (valid targets: {listed(available)})"
            )

    # --- running ---------------------------------------------------------------------------------------------------
    def execute(self, parent_ud: Any = None) -> Optional[str]:
        """Run from the initial state until a transition reaches an outcome of the machine; return it."""
        self.check_consistency()
        with self._state_transitioning_lock:
            self._start_running("this state machine")
            self._preempted_label = None
            self._preempted_state = None
            self._set_current_state(self._initial_state_label)
            try:
                self._copy_input_keys(parent_ud, self.userdata)
                if HOOKS.info_enabled():
                    HOOKS.info(f"State machine starting in initial state {self._current_label!r}")
                self.call_start_cbs()
                outcome: Optional[str] = None
                while outcome is None:
                    if is_shutdown():
                        outcome = self._stop_for_shutdown()
                        break
                    outcome = self._update_once()
                self._copy_output_keys(self.userdata, parent_ud)
                return outcome
            finally:
                self._set_current_state(None)
                self._is_running = False

    def _set_current_state(self, label: Optional[str]) -> None:
        if label is None:
            self._current_label = None
            self._current_state = None
            self._current_transitions = None
        else:
            self._current_label = label
            self._current_state = self._states[label]
            self._current_transitions = self._transitions[label]

    def _update_once(self) -> Optional[str]:
        """Execute the current state once and follow its outcome; return the machine outcome or None."""
        label = self._current_label
        state = self._current_state
        transitions = self._current_transitions
        assert label is not None and transitions is not None
        if self._preempt_requested:
            self._carry_preempt()
        ud = Remapper(
            self.userdata,
            state.get_registered_input_keys(),
            state.get_registered_output_keys(),
            self._remappings[label],
        )
        lock = self._state_transitioning_lock
        lock.release()
        try:
            outcome = run_child(label, state, ud)
        finally:
            lock.acquire()
        target: Any = transitions.get(outcome, _UNBOUND) if isinstance(outcome, str) else _UNBOUND
        if target is _UNBOUND:
            self._raise_unbound(label, state, outcome, transitions)
        nxt = self._states.get(target)
        if nxt is None:
            return self._terminate(label, state, outcome, target)
        self._current_label = target
        self._current_state = nxt
        self._current_transitions = self._transitions[target]
        if HOOKS.info_enabled():
            HOOKS.info(f"State machine transitioning {label!r}:{outcome!r}-->{target!r}")
        if self._transition_cbs:
            self.call_transition_cbs()
        return None

    def _carry_preempt(self) -> None:
        """A preempt is requested before the current state runs: decide whether it still applies."""
        preempted = self._preempted_state
        if preempted is None:
            self._preempt_current_state()  # requested between states: preempt this one before it runs
        elif preempted.preempt_requested():
            self._preempt_current_state()  # the last state ignored it: keep preempting
        else:
            self._preempt_requested = False  # the last state serviced it
            self._preempted_state = None
            self._preempted_label = None

    @staticmethod
    def _raise_unbound(label: str, state: Any, outcome: object, transitions: Dict[str, Optional[str]]) -> None:
        registered = state.get_registered_outcomes()
        if outcome in registered:
            raise InvalidTransitionError(
                f"outcome {outcome!r} of state {label!r} is not bound to any transition target "
                f"(bound: {listed(list(transitions))})"
            )
        raise InvalidTransitionError(
            f"state {label!r} ({type(state).__name__}) returned outcome {outcome!r}, which it does not register "
            f"(registered: {listed(registered)})"
        )

    def _terminate(self, label: str, state: Any, outcome: str, target: Optional[str]) -> str:
        """A transition to an outcome of the machine (or an unbound one falling through)."""
        if self._preempt_requested and self._preempted_state is not None and not state.preempt_requested():
            self.service_preempt()
            self._preempted_state = None
            self._preempted_label = None
        container_outcome = target if target in self._outcomes else outcome
        if container_outcome not in self._outcomes:
            raise InvalidTransitionError(
                f"outcome {outcome!r} of state {label!r} goes to {target!r}, which is neither a state nor an outcome "
                f"of the machine (outcomes: {listed(self.get_registered_outcomes())})"
            )
        if HOOKS.info_enabled():
            HOOKS.info(f"State machine terminating {label!r}:{outcome!r}:{container_outcome!r}")
        self.call_termination_cbs([label], container_outcome)
        return container_outcome

    def _stop_for_shutdown(self) -> Optional[str]:
        HOOKS.warn("shutdown requested: state machine stops before its next state")
        self._preempt_requested = True
        self._preempt_current_state()
        outcome = "preempted" if "preempted" in self._outcomes else None
        self.call_termination_cbs([self._current_label] if self._current_label else [], outcome)
        return outcome

    # --- preemption --------------------------------------------------------------------------------------------------
    def request_preempt(self) -> None:
        """Set this machine's preempt flag and forward the request to the running state."""
        with self._state_transitioning_lock:
            self._preempt_requested = True
            if self._current_state is not None:
                self._preempt_current_state()

    def _preempt_current_state(self) -> None:
        current = self._current_state
        if current is None or self._preempted_state is current:
            return
        if self._preempted_state is not None:
            self._preempted_state.recall_preempt()  # the previously preempted state has terminated
        self._preempted_state = current
        self._preempted_label = self._current_label
        current.request_preempt()


__all__ = ["StateMachine"]
