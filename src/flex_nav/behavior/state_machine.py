"""StateMachine: one active child at a time, transitions by outcome.

::

    sm = StateMachine(outcomes=["finished", "failed"], input_keys=["goal"], userdata={"tries": 0})
    sm.add("Plan", GetPath(), transitions={"planned": "Follow", "failed": "failed"},
           autonomy={"planned": Autonomy.HIGH}, remapping={"target": "goal"})
    sm.add("Follow", FollowPath(), transitions={"done": "finished", "failed": "Plan"})

The first state added is the initial state unless :meth:`StateMachine.set_initial_state` says
otherwise. Every registered outcome of every state needs a transition, to a state label or to an
outcome of the machine; the machine leaves with that outcome. One tick executes the active state
once; a new state is entered (``on_enter`` + first ``execute``) at the next tick, which is due at
once -- unless that state executed less than one period (``1 / rate_hz``) ago, so a loop never runs
a state faster than its rate. A state machine nested in another receives its input keys from the
parent (through its own remapping) and hands its output keys back when it finishes.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping, Optional, Sequence

from flex_nav.behavior.container import Container, child_path, listed
from flex_nav.behavior.state import DUE_SLACK_S, Route, State, StateRuntime
from flex_nav.exceptions import (
    LabelClashError,
    MissingInitialStateError,
    MissingTransitionError,
    UnknownTargetError,
    UnreachableStateError,
    UnregisteredOutcomeError,
)


class StateMachine(Container):
    """Hierarchical state machine with FlexBE semantics (autonomy, locks, forced transitions)."""

    kind = "state machine"

    def __init__(
        self,
        outcomes: Sequence[str],
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
        userdata: Optional[Mapping[str, Any]] = None,
    ) -> None:
        super().__init__(outcomes, input_keys, output_keys, userdata)
        self._transitions: Dict[str, Dict[str, str]] = {}
        self._initial: Optional[str] = None
        self._current: Optional[StateRuntime] = None  # the record of the active child

    def add(
        self,
        label: str,
        state: State,
        transitions: Optional[Mapping[str, str]] = None,
        autonomy: Optional[Mapping[str, object]] = None,
        remapping: Optional[Mapping[str, str]] = None,
    ) -> State:
        """Add ``state`` as ``label``; ``transitions`` maps each of its outcomes to a label or machine outcome."""
        transitions = dict(transitions or {})
        for outcome, target in transitions.items():
            if outcome not in state.outcomes:
                raise UnregisteredOutcomeError(
                    f"{self.kind} {self.path or '(unattached)'}: transition of {label!r} names outcome {outcome!r} "
                    f"that {type(state).__name__} does not register (valid: {listed(state.outcomes)})",
                    self.path,
                    label,
                    outcome,
                    "transition",
                )
            if not isinstance(target, str) or not target:
                raise UnknownTargetError(
                    f"{self.kind} {self.path or '(unattached)'}: transition {label!r}.{outcome} goes to {target!r}, "
                    "not a state label or outcome name",
                    self.path,
                    label,
                    outcome,
                    "transition",
                )
        self._add_child(label, state, remapping, autonomy)
        self._transitions[label] = transitions
        return state

    def set_initial_state(self, label: str) -> None:
        """Start at ``label`` instead of the first state added (checked by validate)."""
        self._initial = label

    @property
    def initial_state(self) -> Optional[str]:
        if self._initial is not None:
            return self._initial
        return next(iter(self._children), None)

    def transitions_of(self, label: str) -> Dict[str, str]:
        return dict(self._transitions[label])

    @property
    def current_state(self) -> Optional[State]:
        """The active child (None when the machine is not running)."""
        current = self._current
        return current.state if current is not None and current.active else None

    # --- validation ------------------------------------------------------------------------------
    def _validate(self, path: str) -> None:  # noqa: PLR0912  (one check per construction error kind)
        labels = list(self._children)
        if not labels:
            raise MissingInitialStateError(f"{self.kind} {path} has no states", path, None, None, "initial")
        initial = self.initial_state
        if initial not in self._children:
            raise MissingInitialStateError(
                f"{self.kind} {path}: initial state {initial!r} is not one of its states (valid: {listed(labels)})",
                path,
                None,
                initial,
                "initial",
            )
        for label in labels:
            if label in self.outcomes:
                raise LabelClashError(
                    f"{self.kind} {path}: state label {label!r} is also an outcome of the machine "
                    f"(outcomes: {listed(self.outcomes)}); rename one",
                    path,
                    label,
                    label,
                    "label",
                )
        targets = [*labels, *self.outcomes]
        for label, child in self._children.items():
            transitions = self._transitions[label]
            for outcome in child.outcomes:
                if outcome not in transitions:
                    raise MissingTransitionError(
                        f"{self.kind} {path}: outcome {outcome!r} of state {label!r} has no transition "
                        f"(valid targets: {listed(targets)})",
                        path,
                        label,
                        outcome,
                        "transition",
                    )
            for outcome, target in transitions.items():
                if target not in self._children and target not in self.outcomes:
                    raise UnknownTargetError(
                        f"{self.kind} {path}: transition {label!r}.{outcome} goes to unknown target {target!r} "
                        f"(valid: {listed(targets)})",
                        path,
                        label,
                        outcome,
                        "transition",
                    )
        reached = {initial}
        frontier: List[str] = [initial]
        while frontier:
            for target in self._transitions[frontier.pop()].values():
                if target in self._children and target not in reached:
                    reached.add(target)
                    frontier.append(target)
        for label in labels:
            if label not in reached:
                raise UnreachableStateError(
                    f"{self.kind} {path}: state {label!r} cannot be reached from the initial state {initial!r} "
                    f"(reachable: {listed([lb for lb in labels if lb in reached])})",
                    path,
                    label,
                    label,
                    "state",
                )
        self._validate_keys(path)
        self._validate_children(path)

    # --- running ------------------------------------------------------------------------------------
    def _make_routes(self, label: str, child: State) -> Dict[str, Route]:
        levels = self._autonomy[label]
        routes: Dict[str, Route] = {}
        for outcome, target in self._transitions[label].items():
            nxt = self._children.get(target)
            if nxt is not None:
                path = child_path(self.path, target)
                routes[outcome] = Route(nxt.__flex_nav_runtime__, None, levels.get(outcome, 0), target, path)
            else:
                routes[outcome] = Route(None, target, levels.get(outcome, 0), target, "")
        return routes

    def _activate(self, now: float) -> None:
        super()._activate(now)
        initial = self._children[self.initial_state or ""].__flex_nav_runtime__
        self._current = initial
        initial.activate(now)

    def _active_children(self) -> List[StateRuntime]:
        current = self._current
        return [current] if current is not None and current.active else []

    def _tick(self, now: float) -> Optional[str]:
        rt = self.__flex_nav_runtime__
        ctx = rt.ctx
        assert ctx is not None  # attached before any tick
        child = self._current
        assert child is not None  # activated before any tick
        outcome: Optional[str]
        if child.pending is not None:  # an outcome waits (autonomy, lock) or was forced
            resolved = self._resolve(child, now)
            if resolved is None:
                rt.due = math.inf
                return None
            outcome, route, forced = resolved
        else:
            if child.due > now + DUE_SLACK_S:
                rt.due = child.due
                return None
            outcome = child.tick(now)
            if outcome is None:
                rt.due = child.due
                return None
            try:
                route = child.routes[outcome]
            except (KeyError, TypeError):
                route = self._route(child, outcome)  # raises with the valid outcomes
            needs_check = ctx.lock_count or (ctx.gate and route.required >= ctx.autonomy)
            if needs_check and self._must_wait(child, outcome, route, False, now):
                rt.due = math.inf
                return None
            forced = False
            child.leave()
        # the transition fires
        ctx.changed = True
        nxt = route.next_state
        if nxt is not None:
            self._current = nxt
            nxt.activate(now)
            rt.due = nxt.due
            if ctx.context.hooks.transition:
                ctx.emit_transition(now, child.path, outcome, route.target, route.target_path, route.required, forced)
            return None
        rt.due = math.inf
        if ctx.context.hooks.transition:
            ctx.emit_transition(now, child.path, outcome, route.target, "", route.required, forced)
        return route.container_outcome


__all__ = ["StateMachine", "child_path"]
