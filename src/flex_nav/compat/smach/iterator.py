"""SMACH's Iterator: run one contained state once per item of an iterable.

::

    it = smach.Iterator(outcomes=["succeeded", "aborted"], input_keys=[], output_keys=[],
                        it=lambda: range(3), it_label="index", exhausted_outcome="succeeded")
    with it:
        smach.Iterator.set_contained_state("BODY", body, loop_outcomes=["continue"])

Before each run the current item is stored in the iterator's userdata under ``it_label``; the
contained state receives that userdata itself (as in SMACH, so it sees every key). An outcome in
``loop_outcomes`` continues with the next item; any other outcome (or one listed in
``break_outcomes``) stops the loop, and the iterator returns it, renamed through
``final_outcome_map``. When the items run out it returns ``exhausted_outcome``. ``it`` may be a
callable returning an iterable (evaluated at each execution). A preempt request is forwarded to the
running contained state and stops the loop after it returns.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

from flex_nav.compat.smach._hooks import HOOKS
from flex_nav.compat.smach.container import Container, check_state_interface, listed, run_child, smach_construction
from flex_nav.compat.smach.user_data import UserData
from flex_nav.compat.smach.util import is_shutdown, names
from flex_nav.exceptions import InvalidStateError, InvalidTransitionError

Items = Union[Iterable[Any], Callable[[], Iterable[Any]]]


class Iterator(Container):
    """Loops a contained state over the items of ``it``."""

    def __init__(  # noqa: PLR0917  (SMACH's signature)
        self,
        outcomes: Sequence[str],
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
        it: Items = (),
        it_label: str = "it_data",
        exhausted_outcome: str = "exhausted",
    ) -> None:
        outcome_list = names("outcomes", outcomes, "Iterator")
        (exhausted_outcome,) = names("exhausted_outcome", [exhausted_outcome], "Iterator")
        if exhausted_outcome not in outcome_list:
            outcome_list.append(exhausted_outcome)
        super().__init__(outcome_list, input_keys, output_keys)
        self._items: Items = it
        (self._items_label,) = names("it_label", [it_label], "Iterator")
        self._exhausted_outcome = exhausted_outcome
        self._state_label = ""
        self._state: Any = None
        self._loop_outcomes: List[str] = []
        self._break_outcomes: List[str] = []
        self._final_outcome_map: Dict[str, str] = {}

    # --- construction -----------------------------------------------------------------------------------------
    def _set_iteritems(self, it: Items, it_label: str = "it_data") -> None:
        self._items = it
        (self._items_label,) = names("it_label", [it_label], "Iterator")

    def _set_contained_state(
        self,
        label: str,
        state: Any,
        loop_outcomes: Sequence[str] = (),
        break_outcomes: Sequence[str] = (),
        final_outcome_map: Optional[Mapping[str, str]] = None,
    ) -> Any:
        label = check_state_interface(label, state, "Iterator")
        registered = list(state.get_registered_outcomes())
        loops = names("loop_outcomes", loop_outcomes, f"Iterator state {label!r}")
        breaks = names("break_outcomes", break_outcomes, f"Iterator state {label!r}")
        final = dict(final_outcome_map or {})
        for what, values in (("loop_outcomes", loops), ("break_outcomes", breaks), ("final_outcome_map", list(final))):
            unknown = [o for o in values if o not in registered]
            if unknown:
                raise InvalidTransitionError(
                    f"Iterator state {label!r}: {what} names {listed(unknown)}, which it does not register "
                    f"(registered: {listed(registered)})"
                )
        if loops and breaks:
            HOOKS.warn("Iterator: both loop_outcomes and break_outcomes given; break_outcomes win")
        if breaks:
            loops = [o for o in registered if o not in breaks]
        else:
            breaks = [o for o in registered if o not in loops]
        self._state_label = label
        self._state = state
        self._loop_outcomes = loops
        self._break_outcomes = breaks
        self._final_outcome_map = final
        return state

    set_iteritems = smach_construction(_set_iteritems)
    set_contained_state = smach_construction(_set_contained_state)

    # --- introspection ------------------------------------------------------------------------------------------
    def get_children(self) -> Dict[str, Any]:
        return {self._state_label: self._state} if self._state is not None else {}

    def __getitem__(self, key: str) -> Any:
        if self._state is None or key != self._state_label:
            raise KeyError(f"Iterator has no state {key!r} (its state: {self._state_label or 'none'})")
        return self._state

    def get_initial_states(self) -> List[str]:
        return [self._state_label] if self._state is not None else []

    def set_initial_state(self, initial_states: Sequence[str], userdata: Optional[UserData] = None) -> None:
        unknown = [s for s in initial_states if s != self._state_label]
        if unknown:
            raise InvalidStateError(f"Iterator has no state {unknown} (its state: {self._state_label or 'none'})")
        if userdata is not None:
            self.userdata.update(userdata)

    def get_active_states(self) -> List[str]:
        return [self._state_label] if self._is_running else []

    def get_internal_edges(self) -> List[Tuple[str, str, Optional[str]]]:
        label = self._state_label
        edges: List[Tuple[str, str, Optional[str]]] = [(o, label, label) for o in self._loop_outcomes]
        for outcome in self._break_outcomes:
            final = self._final_outcome_map.get(outcome, outcome)
            edges.append((outcome, self._state_label, final))
        return edges

    def check_consistency(self) -> None:
        if self._state is None:
            raise InvalidStateError("Iterator has no contained state (use set_contained_state)")
        for outcome in self._break_outcomes:
            final = self._final_outcome_map.get(outcome, outcome)
            if final not in self._outcomes:
                raise InvalidTransitionError(
                    f"Iterator: break outcome {outcome!r} of {self._state_label!r} ends the iterator with {final!r}, "
                    f"which is not one of its outcomes ({listed(self.get_registered_outcomes())})"
                )

    # --- running -------------------------------------------------------------------------------------------------
    def execute(self, parent_ud: Any = None) -> Optional[str]:
        self.check_consistency()
        self._start_running("this Iterator")
        try:
            self._copy_input_keys(parent_ud, self.userdata)
            self.call_start_cbs()
            items = self._items() if callable(self._items) else self._items
            outcome = self._exhausted_outcome  # unless the loop breaks
            for item in items:
                if is_shutdown():
                    HOOKS.warn("shutdown requested: Iterator stops")
                    outcome = "preempted" if "preempted" in self._outcomes else self._exhausted_outcome
                    break
                self.userdata[self._items_label] = item
                if self._preempt_requested:
                    self._state.request_preempt()
                result = run_child(self._state_label, self._state, self.userdata)
                if result not in self._state.get_registered_outcomes():
                    raise InvalidTransitionError(
                        f"Iterator state {self._state_label!r} returned outcome {result!r}, which it does not "
                        f"register (registered: {listed(self._state.get_registered_outcomes())})"
                    )
                if self._preempt_requested or result not in self._loop_outcomes:
                    self._preempt_requested = False
                    outcome = result
                    break
                self.call_transition_cbs()
            outcome = self._final_outcome_map.get(outcome, outcome)
            if outcome not in self._outcomes:
                raise InvalidTransitionError(
                    f"Iterator ends with {outcome!r}, which is not one of its outcomes "
                    f"({listed(self.get_registered_outcomes())})"
                )
            self._copy_output_keys(self.userdata, parent_ud)
            self.call_termination_cbs([self._state_label], outcome)
            return outcome
        finally:
            self._is_running = False

    def request_preempt(self) -> None:
        self._preempt_requested = True
        if self._is_running and self._state is not None:
            self._state.request_preempt()


__all__ = ["Iterator"]
