"""ConcurrencyContainer: all children active at once, ticked one after the other in one thread.

::

    cc = ConcurrencyContainer(
        outcomes=["arrived", "blocked", "failed"],
        conditions=[
            ("arrived", [("Follow", "done")]),
            ("blocked", [("Bumper", "hit")]),
            ("failed", [("Follow", "failed")]),
        ],
    )
    cc.add("Follow", FollowPath())
    cc.add("Bumper", WatchBumper())

Each tick executes every running child that is due (each at its own rate). A child that returns
an outcome (after the autonomy and lock gating of its ``autonomy`` levels) is exited and stays
finished. After any child finishes, the ``conditions`` are checked in order: each is an AND-list of
``(child, outcome)`` pairs over the finished children; the first one that holds gives the
container's outcome and every still-running child is exited (``on_exit``). If all children have
finished and no condition holds, the behavior fails with a message naming the outcomes seen.
No thread is started, ever.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

from flex_nav.behavior.container import Container, listed
from flex_nav.behavior.state import DUE_SLACK_S, State, StateRuntime
from flex_nav.exceptions import (
    BehaviorConstructionError,
    BehaviorRuntimeError,
    MissingInitialStateError,
    UnknownTargetError,
    UnregisteredOutcomeError,
)

Condition = Tuple[str, Sequence[Tuple[str, str]]]


class ConcurrencyContainer(Container):
    """Runs its children concurrently (single-threaded); ordered AND-conditions decide its outcome."""

    kind = "concurrency container"

    def __init__(
        self,
        outcomes: Sequence[str],
        conditions: Sequence[Condition] = (),
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
        userdata: Optional[Mapping[str, Any]] = None,
    ) -> None:
        super().__init__(outcomes, input_keys, output_keys, userdata)
        self._conditions: List[Tuple[str, Tuple[Tuple[str, str], ...]]] = []
        for condition in conditions:
            self.add_condition(*condition)
        self._running: Tuple[StateRuntime, ...] = ()  # records of the children that did not finish
        self._finished: Dict[str, str] = {}

    def add(
        self,
        label: str,
        state: State,
        remapping: Optional[Mapping[str, str]] = None,
        autonomy: Optional[Mapping[str, object]] = None,
    ) -> State:
        """Add a concurrent child. ``autonomy`` gates its outcomes like a transition's level."""
        self._add_child(label, state, remapping, autonomy)
        return state

    def add_condition(self, outcome: str, when: Sequence[Tuple[str, str]]) -> None:
        """Append a condition: the container returns ``outcome`` once all ``(child, outcome)`` pairs hold."""
        try:
            pairs = tuple((str(child), str(child_outcome)) for child, child_outcome in when)
        except (TypeError, ValueError) as err:
            raise BehaviorConstructionError(
                f"{self.kind}: condition for {outcome!r} must be a list of (state, outcome) pairs, got {when!r}",
                self.path,
                None,
                outcome,
                "condition",
            ) from err
        self._conditions.append((outcome, pairs))

    @property
    def conditions(self) -> List[Tuple[str, Tuple[Tuple[str, str], ...]]]:
        return list(self._conditions)

    # --- validation ------------------------------------------------------------------------------
    def _validate(self, path: str) -> None:
        if not self._children:
            raise MissingInitialStateError(f"{self.kind} {path} has no states", path, None, None, "initial")
        if not self._conditions:
            raise BehaviorConstructionError(
                f"{self.kind} {path} has no conditions (each maps AND-ed (state, outcome) pairs to one of its "
                f"outcomes: {listed(self.outcomes)})",
                path,
                None,
                None,
                "condition",
            )
        labels = list(self._children)
        for outcome, pairs in self._conditions:
            if outcome not in self.outcomes:
                raise UnregisteredOutcomeError(
                    f"{self.kind} {path}: condition outcome {outcome!r} is not an outcome of the container "
                    f"(valid: {listed(self.outcomes)})",
                    path,
                    None,
                    outcome,
                    "condition",
                )
            if not pairs:
                raise BehaviorConstructionError(
                    f"{self.kind} {path}: condition for {outcome!r} lists no (state, outcome) pairs",
                    path,
                    None,
                    outcome,
                    "condition",
                )
            for label, child_outcome in pairs:
                child = self._children.get(label)
                if child is None:
                    raise UnknownTargetError(
                        f"{self.kind} {path}: condition for {outcome!r} names unknown state {label!r} "
                        f"(valid: {listed(labels)})",
                        path,
                        label,
                        outcome,
                        "condition",
                    )
                if child_outcome not in child.outcomes:
                    raise UnregisteredOutcomeError(
                        f"{self.kind} {path}: condition for {outcome!r} names outcome {child_outcome!r} of "
                        f"{label!r} that it does not register (valid: {listed(child.outcomes)})",
                        path,
                        label,
                        outcome,
                        "condition",
                    )
        self._validate_keys(path)
        self._validate_children(path)

    # --- running ------------------------------------------------------------------------------------
    def _activate(self, now: float) -> None:
        super()._activate(now)
        self._finished = {}
        self._running = tuple(child.__flex_nav_runtime__ for child in self._children.values())
        for child in self._running:
            child.activate(now)

    def _active_children(self) -> List[StateRuntime]:
        return [child for child in self._running if child.active]

    def _tick(self, now: float) -> Optional[str]:  # noqa: PLR0912  (the hot path, kept in one piece)
        rt = self.__flex_nav_runtime__
        ctx = rt.ctx
        assert ctx is not None
        finished: Optional[List[StateRuntime]] = None
        due = math.inf
        # a child may be woken during this tick (a priority container finishing in a later child
        # releases an earlier one): its wake() lowers rt.due, which is folded in at the end
        rt.due = math.inf
        for child in self._running:
            if child.pending is not None:
                resolved = self._resolve(child, now)
                if resolved is None:
                    continue
                outcome, route, forced = resolved
            else:
                child_due = child.due
                if child_due > now + DUE_SLACK_S:
                    due = min(due, child_due)
                    continue
                result = child.tick(now)
                if result is None:
                    due = min(due, child.due)
                    continue
                outcome = result
                route = self._route(child, outcome)
                if (ctx.lock_count or (ctx.gate and route.required >= ctx.autonomy)) and self._must_wait(
                    child, outcome, route, False, now
                ):
                    continue
                forced = False
                child.leave()
            self._finished[child.label] = outcome
            if finished is None:
                finished = [child]
            else:
                finished.append(child)
            if ctx.context.hooks.transition:
                ctx.emit_transition(now, child.path, outcome, "", "", route.required, forced)
        if finished is not None:
            ctx.changed = True
            self._running = tuple(c for c in self._running if c not in finished)
            matched = self._match()
            if matched is not None:
                for child in self._running:
                    child.abort()
                self._running = ()
                rt.due = math.inf
                return matched
            if not self._running:
                seen = ", ".join(f"{label}={outcome}" for label, outcome in self._finished.items())
                raise BehaviorRuntimeError(
                    f"{self.kind} {rt.path}: all states finished ({seen}) and no condition holds "
                    f"(conditions: {self._describe_conditions()})"
                )
        rt.due = min(rt.due, due)
        return None

    def _match(self) -> Optional[str]:
        finished = self._finished
        for outcome, pairs in self._conditions:
            if all(finished.get(label) == child_outcome for label, child_outcome in pairs):
                return outcome
        return None

    def _describe_conditions(self) -> str:
        return "; ".join(
            f"{outcome} <- {' and '.join(f'{label}={o}' for label, o in pairs)}" for outcome, pairs in self._conditions
        )
