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
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence

from flex_nav.behavior.container import Container, _listed, child_path
from flex_nav.behavior.state import Route, State

if TYPE_CHECKING:
    from flex_nav.behavior.context import BehaviorContext
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
        self._current: Optional[State] = None

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
                    f"{self.kind} {self._path or '(unattached)'}: transition of {label!r} names outcome {outcome!r} "
                    f"that {type(state).__name__} does not register (valid: {_listed(state.outcomes)})",
                    self._path,
                    label,
                    outcome,
                    "transition",
                )
            if not isinstance(target, str) or not target:
                raise UnknownTargetError(
                    f"{self.kind} {self._path or '(unattached)'}: transition {label!r}.{outcome} goes to {target!r}, "
                    "not a state label or outcome name",
                    self._path,
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
        return current if current is not None and current._active else None

    # --- validation ------------------------------------------------------------------------------
    def _validate(self, path: str) -> None:  # noqa: PLR0912  (one check per construction error kind)
        labels = list(self._children)
        if not labels:
            raise MissingInitialStateError(f"{self.kind} {path} has no states", path, None, None, "initial")
        initial = self.initial_state
        if initial not in self._children:
            raise MissingInitialStateError(
                f"{self.kind} {path}: initial state {initial!r} is not one of its states (valid: {_listed(labels)})",
                path,
                None,
                initial,
                "initial",
            )
        for label in labels:
            if label in self._outcomes:
                raise LabelClashError(
                    f"{self.kind} {path}: state label {label!r} is also an outcome of the machine "
                    f"(outcomes: {_listed(self._outcomes)}); rename one",
                    path,
                    label,
                    label,
                    "label",
                )
        targets = [*labels, *self._outcomes]
        for label, child in self._children.items():
            transitions = self._transitions[label]
            for outcome in child.outcomes:
                if outcome not in transitions:
                    raise MissingTransitionError(
                        f"{self.kind} {path}: outcome {outcome!r} of state {label!r} has no transition "
                        f"(valid targets: {_listed(targets)})",
                        path,
                        label,
                        outcome,
                        "transition",
                    )
            for outcome, target in transitions.items():
                if target not in self._children and target not in self._outcomes:
                    raise UnknownTargetError(
                        f"{self.kind} {path}: transition {label!r}.{outcome} goes to unknown target {target!r} "
                        f"(valid: {_listed(targets)})",
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
                    f"(reachable: {_listed([lb for lb in labels if lb in reached])})",
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
                routes[outcome] = Route(nxt, None, levels.get(outcome, 0), target, child_path(self._path, target))
            else:
                routes[outcome] = Route(None, target, levels.get(outcome, 0), target, "")
        return routes

    def _activate(self, now: float) -> None:
        super()._activate(now)
        initial = self._children[self.initial_state or ""]
        self._current = initial
        initial._activate(now)

    def _active_children(self) -> List[State]:
        current = self._current
        return [current] if current is not None and current._active else []

    def _tick(self, now: float) -> Optional[str]:
        ctx: BehaviorContext = self._ctx  # type: ignore[assignment]  # attached before any tick
        child: State = self._current  # type: ignore[assignment]  # activated before any tick
        outcome: Optional[str]
        if child._pending is not None:  # an outcome waits (autonomy, lock) or was forced
            resolved = self._resolve(child, now)
            if resolved is None:
                self._due = math.inf
                return None
            outcome, route, forced = resolved
        else:
            if child._due > now:
                self._due = child._due
                return None
            outcome = child._tick(now)
            if outcome is None:
                self._due = child._due
                return None
            try:
                route = child._routes[outcome]
            except (KeyError, TypeError):
                route = self._route(child, outcome)  # raises with the valid outcomes
            needs_check = ctx._lock_count or (ctx._gate and route.required >= ctx._autonomy)
            if needs_check and self._must_wait(child, outcome, route, False, now):
                self._due = math.inf
                return None
            forced = False
            child._leave()
        # the transition fires
        ctx._changed = True
        nxt = route.next_state
        if nxt is not None:
            self._current = nxt
            nxt._activate(now)
            self._due = nxt._due
            if ctx.hooks.transition:
                ctx._emit_transition(now, child._path, outcome, route.target, route.target_path, route.required, forced)
            return None
        self._due = math.inf
        if ctx.hooks.transition:
            ctx._emit_transition(now, child._path, outcome, route.target, "", route.required, forced)
        return route.container_outcome


__all__ = ["StateMachine", "child_path"]
