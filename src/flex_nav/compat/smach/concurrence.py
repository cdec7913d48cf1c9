"""SMACH's Concurrence: every child runs at once, in its own thread; the outcome follows a policy.

::

    cc = smach.Concurrence(outcomes=["succeeded", "aborted"], default_outcome="aborted",
                           outcome_map={"succeeded": {"MOVE": "succeeded", "LOOK": "done"}},
                           child_termination_cb=lambda outcomes: outcomes["MOVE"] is not None)
    with cc:
        smach.Concurrence.add("MOVE", Move())
        smach.Concurrence.add("LOOK", Look())

SMACH states block in ``execute``, so concurrency needs threads: one per child per execution of the
container (flex_nav's own engine never does this; this is the compatibility layer's price). The
container finishes when every child has finished. Each time a child finishes, ``child_termination_cb``
(if given) receives ``{label: outcome or None}``; returning True preempts every child still running,
a list of labels preempts those. The outcome is, in order of precedence: ``outcome_cb(outcomes)``
when it returns a string; the ``outcome_map`` entry whose every ``label: outcome`` pair holds (the one
with the most pairs when several hold; the first listed on a tie); ``default_outcome``.

Preemption: ``request_preempt()`` is forwarded to every running child; when they are done, the
container services its own request if every child serviced its one (unserviced child requests are
recalled). A child that raises makes the container preempt the others, wait for them, and raise
:class:`InvalidUserCodeError` naming it; a child that returns an unregistered outcome (or None) gives
:class:`InvalidTransitionError`. With a shutdown check set, running children are preempted once
shutdown is detected, and if they have not stopped ``SHUTDOWN_GRACE_S`` later the container raises
:class:`InvalidStateError` naming them (their threads are daemons and do not hold the process).
"""

from __future__ import annotations

import copy
import threading
import time
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Set, Tuple

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
from flex_nav.compat.smach.util import is_shutdown
from flex_nav.exceptions import InvalidStateError, InvalidTransitionError, InvalidUserCodeError

WAIT_SLICE_S = 0.1  # [s] longest single wait of the container thread (bounds shutdown detection)
SHUTDOWN_GRACE_S = 5.0  # [s] how long preempted children may take to stop after shutdown


class Concurrence(Container):
    """Split-join concurrency of SMACH states (one thread per child while the container executes)."""

    def __init__(  # noqa: PLR0917  (SMACH's signature)
        self,
        outcomes: Sequence[str],
        default_outcome: str,
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
        outcome_map: Optional[Mapping[str, Mapping[str, str]]] = None,
        outcome_cb: Optional[Callable[[Dict[str, Optional[str]]], Optional[str]]] = None,
        child_termination_cb: Optional[Callable[[Dict[str, Optional[str]]], Any]] = None,
    ) -> None:
        super().__init__(outcomes, input_keys, output_keys)
        registered = self.get_registered_outcomes()
        errors: List[str] = []
        if not isinstance(default_outcome, str) or default_outcome not in registered:
            errors.append(f"default outcome {default_outcome!r} is not one of its outcomes ({listed(registered)})")
        outcome_map = dict(outcome_map or {})
        for outcome, conditions in outcome_map.items():
            if outcome not in registered:
                errors.append(f"outcome_map names outcome {outcome!r}, which is not one of {listed(registered)}")
            if not isinstance(conditions, Mapping) or not conditions:
                errors.append(f"outcome_map[{outcome!r}] must be a non-empty mapping of child label -> outcome")
        # runtime checks: SMACH code calling this is not type-checked
        if outcome_cb is not None and not callable(outcome_cb):
            errors.append(f"outcome_cb {outcome_cb!r} is not callable")  # type: ignore[unreachable]
        if child_termination_cb is not None and not callable(child_termination_cb):
            errors.append(f"child_termination_cb {child_termination_cb!r} is not callable")  # type: ignore[unreachable]
        if errors:
            raise InvalidStateError("errors in the outcome policy of a Concurrence: " + "; ".join(errors))
        self._default_outcome = default_outcome
        self._outcome_map: Dict[str, Dict[str, str]] = {o: dict(c) for o, c in outcome_map.items()}
        self._outcome_cb = outcome_cb
        self._child_termination_cb = child_termination_cb
        self._states: Dict[str, Any] = {}
        self._remappings: Dict[str, Dict[str, str]] = {}
        # one execution's bookkeeping, guarded by _cond
        self._cond = threading.Condition()
        self._child_outcomes: Dict[str, Optional[str]] = {}
        self._finished: Set[str] = set()
        self._errors: Dict[str, BaseException] = {}
        self._to_preempt: Set[str] = set()  # children the container must preempt (termination cb, error)
        self._preempted: Set[str] = set()  # children the container has preempted

    # --- construction --------------------------------------------------------------------------------------
    def _add(self, label: str, state: Any, remapping: Optional[Mapping[str, str]] = None) -> Any:
        label = check_state_interface(label, state, "Concurrence")
        if label in self._states:
            raise InvalidStateError(
                f"Concurrence: child label {label!r} is already used (labels: {listed(list(self._states))})"
            )
        self._states[label] = state
        self._remappings[label] = remapping_of(remapping, f"Concurrence child {label!r}")
        return state

    add = smach_construction(_add)

    # --- introspection ----------------------------------------------------------------------------------------
    def get_children(self) -> Dict[str, Any]:
        return dict(self._states)

    def __getitem__(self, key: str) -> Any:
        return labelled_child(self._states, key, "Concurrence has no child", "children")

    def get_initial_states(self) -> List[str]:
        return list(self._states)

    def set_initial_state(self, initial_states: Sequence[str], userdata: Optional[UserData] = None) -> None:
        """All children always start; only ``userdata`` is merged (as in SMACH, which ignores the labels with a
        warning: they may name children added later)."""
        if initial_states and set(initial_states) != set(self._states):
            HOOKS.warn(
                f"Concurrence starts all its children (now: {listed(list(self._states))}); "
                f"initial states {list(initial_states)} ignored"
            )
        if userdata is not None:
            self.userdata.update(userdata)

    def get_active_states(self) -> List[str]:
        with self._cond:
            if not self._is_running:
                return []
            return [label for label in self._states if label not in self._finished]

    def get_internal_edges(self) -> List[Tuple[str, str, Optional[str]]]:
        return [
            (child_outcome, label, outcome)
            for outcome, conditions in self._outcome_map.items()
            for label, child_outcome in conditions.items()
        ]

    def check_consistency(self) -> None:
        if not self._states:
            raise InvalidStateError("Concurrence has no children")
        for outcome, conditions in self._outcome_map.items():
            for label, child_outcome in conditions.items():
                child = self._states.get(label)
                if child is None:
                    raise InvalidTransitionError(
                        f"outcome_map[{outcome!r}] names child {label!r}, which is not in the Concurrence "
                        f"(children: {listed(list(self._states))})"
                    )
                if child_outcome not in child.get_registered_outcomes():
                    raise InvalidTransitionError(
                        f"outcome_map[{outcome!r}] expects outcome {child_outcome!r} of {label!r}, which it does not "
                        f"register (registered: {listed(child.get_registered_outcomes())})"
                    )

    # --- running --------------------------------------------------------------------------------------------------
    def execute(self, parent_ud: Any = None) -> Optional[str]:
        """Run every child in its own thread until all have finished; return the container outcome."""
        self.check_consistency()
        with self._cond:
            self._start_running("this Concurrence")
            self._child_outcomes = dict.fromkeys(self._states)
            self._finished = set()
            self._errors = {}
            self._to_preempt = set()
            self._preempted = set()
        try:
            self._copy_input_keys(parent_ud, self.userdata)
            self.call_start_cbs()
            threads = [
                threading.Thread(target=self._run, args=(label,), name=f"smach_concurrence:{label}", daemon=True)
                for label in self._states
            ]
            for thread in threads:
                thread.start()
            self._wait_for_children()
            for thread in threads:
                thread.join(WAIT_SLICE_S)  # each has reported; this only lets it return
            self._raise_child_errors()
            outcome = self._outcome()
            self._settle_preempts()
            self.call_termination_cbs(list(self._states), outcome)
            self._copy_output_keys(self.userdata, parent_ud)
            return outcome
        finally:
            with self._cond:
                self._is_running = False

    def _run(self, label: str) -> None:
        """Thread body: execute one child and report to the container."""
        state = self._states[label]
        error: Optional[BaseException] = None
        outcome: Any = None
        try:
            self.call_transition_cbs()
            outcome = run_child(
                label,
                state,
                Remapper(
                    self.userdata,
                    state.get_registered_input_keys(),
                    state.get_registered_output_keys(),
                    self._remappings[label],
                ),
            )
        except BaseException as err:
            error = err
        with self._cond:
            self._child_outcomes[label] = outcome
            self._finished.add(label)
            if error is not None:
                self._errors[label] = error
                self._to_preempt.update(self._states)
            self._cond.notify_all()
        if error is not None:
            return
        try:
            self.call_transition_cbs()
            stop = self._child_termination_cb(dict(self._child_outcomes)) if self._child_termination_cb else False
        except BaseException as err:
            with self._cond:
                self._errors.setdefault(label, err)
                self._to_preempt.update(self._states)
                self._cond.notify_all()
            return
        if stop:
            with self._cond:
                if stop is True or not isinstance(stop, (list, tuple, set, frozenset)):
                    self._to_preempt.update(self._states)
                else:
                    self._to_preempt.update(str(s) for s in stop)
                self._cond.notify_all()

    def _wait_for_children(self) -> None:
        shutdown_deadline: Optional[float] = None
        while True:
            with self._cond:
                running = [label for label in self._states if label not in self._finished]
                if not running:
                    return
                if self._preempt_requested:
                    self._to_preempt.update(running)
                preempt = [label for label in running if label in self._to_preempt and label not in self._preempted]
                self._preempted.update(preempt)
                if not preempt:
                    self._cond.wait(WAIT_SLICE_S)
            for label in preempt:  # outside the lock: a child's request_preempt may take time
                try:
                    self._states[label].request_preempt()
                except Exception as err:
                    with self._cond:
                        self._errors.setdefault(label, err)
            if is_shutdown():
                now = time.monotonic()
                if shutdown_deadline is None:
                    HOOKS.warn("shutdown requested: preempting the running children of a Concurrence")
                    shutdown_deadline = now + SHUTDOWN_GRACE_S
                    with self._cond:
                        self._to_preempt.update(self._states)
                elif now > shutdown_deadline:
                    raise InvalidStateError(
                        f"Concurrence children {listed(running)} did not stop within {SHUTDOWN_GRACE_S} s of shutdown"
                    )

    def _raise_child_errors(self) -> None:
        if not self._errors:
            return
        label = next(lb for lb in self._states if lb in self._errors)
        error = self._errors[label]
        others = [lb for lb in self._states if lb in self._errors and lb != label]
        also = f" (also failed: {listed(others)})" if others else ""
        if isinstance(error, InvalidUserCodeError) and error.__cause__ is not None:
            cause: BaseException = error.__cause__
        else:
            cause = error
        raise InvalidUserCodeError(
            f"concurrent state {label!r} failed: {type(cause).__name__}: {cause}{also}"
        ) from cause

    def _outcome(self) -> str:
        outcomes = self._child_outcomes
        for label, state in self._states.items():
            registered = state.get_registered_outcomes()
            if outcomes[label] not in registered:
                raise InvalidTransitionError(
                    f"concurrent state {label!r} returned outcome {outcomes[label]!r}, which it does not register "
                    f"(registered: {listed(registered)})"
                )
        if self._outcome_cb is not None:
            try:
                chosen = self._outcome_cb(copy.copy(outcomes))
            except Exception as err:
                raise InvalidUserCodeError(f"outcome_cb of a Concurrence raised {type(err).__name__}: {err}") from err
            if chosen is not None:
                if not isinstance(chosen, str) or chosen not in self._outcomes:
                    raise InvalidTransitionError(
                        f"outcome_cb of a Concurrence returned {chosen!r}, which is not one of its outcomes "
                        f"({listed(self.get_registered_outcomes())})"
                    )
                return chosen
        best: Optional[str] = None
        best_size = 0
        for outcome, conditions in self._outcome_map.items():
            if len(conditions) > best_size and all(outcomes.get(lb) == o for lb, o in conditions.items()):
                best, best_size = outcome, len(conditions)
        return best if best is not None else self._default_outcome

    def _settle_preempts(self) -> None:
        unserviced = [label for label, state in self._states.items() if state.preempt_requested()]
        for label in unserviced:
            self._states[label].recall_preempt()
        if self._preempt_requested:
            if unserviced:
                HOOKS.warn(f"Concurrence children {listed(unserviced)} did not service the preempt request")
            else:
                self.service_preempt()

    # --- preemption ------------------------------------------------------------------------------------------
    def request_preempt(self) -> None:
        """Preempt every running child (the container thread forwards the request)."""
        with self._cond:
            self._preempt_requested = True
            self._cond.notify_all()


__all__ = ["Concurrence"]
