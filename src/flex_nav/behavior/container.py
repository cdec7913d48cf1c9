"""Container: what state machines, concurrency and priority containers share.

A container is a :class:`~flex_nav.behavior.state.State` whose children are states. It owns:

- the children by label, each with its ``remapping`` (child key -> container key) and per-outcome
  ``autonomy`` (required level, default ``Autonomy.OFF``);
- a userdata store (a dict): on activation it holds the ``userdata`` defaults given to the
  constructor plus the container's input keys copied (by reference) from its parent; when the
  container finishes, its output keys are copied back to the parent. Each activation starts fresh;
- the gating of child outcomes: autonomy (request and wait for the operator), locks (hold an
  outcome that would leave a locked container) and forced outcomes.

Validation (``validate()``) runs when a behavior is loaded or started, before the first tick; each
error is a :class:`~flex_nav.exceptions.BehaviorConstructionError` subclass that names the bad item
and the valid choices and carries ``container``/``label``/``item``/``field`` for loaders.
"""

from __future__ import annotations

import math
from typing import Any, Dict, FrozenSet, Iterator, List, Mapping, Optional, Sequence, Tuple

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.state import Pending, PendingReason, Route, State
from flex_nav.behavior.userdata import ReadSpec, UserDataView
from flex_nav.exceptions import (
    BehaviorConstructionError,
    BehaviorRuntimeError,
    ConfigError,
    LabelClashError,
    UndeclaredKeyError,
    UnregisteredOutcomeError,
    UserDataKeyError,
    choices_message,
)


def child_path(parent_path: str, label: str) -> str:
    return f"{parent_path.rstrip('/')}/{label}"


def _listed(values: Sequence[str] | FrozenSet[str]) -> str:
    return ", ".join(values) if values else "none"


class Container(State):
    """Base of StateMachine, ConcurrencyContainer and PriorityContainer (not used directly)."""

    kind = "container"  # for messages: "state machine", "concurrency container", ...

    def __init__(
        self,
        outcomes: Sequence[str],
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
        userdata: Optional[Mapping[str, Any]] = None,
    ) -> None:
        super().__init__(outcomes, input_keys, output_keys)
        if userdata is not None and not isinstance(userdata, Mapping):
            raise ConfigError(f"{type(self).__name__}: userdata defaults must be a mapping, got {userdata!r}")
        self._defaults: Dict[str, Any] = dict(userdata or {})
        self._children: Dict[str, State] = {}
        self._remapping: Dict[str, Dict[str, str]] = {}
        self._autonomy: Dict[str, Dict[str, int]] = {}
        self._data: Dict[str, Any] = {}
        self._protected: FrozenSet[str] = frozenset()

    # --- building ----------------------------------------------------------------------------------
    def _add_child(
        self,
        label: str,
        state: State,
        remapping: Optional[Mapping[str, str]],
        autonomy: Optional[Mapping[str, object]],
    ) -> None:
        where = self._path or "(unattached)"
        if not isinstance(label, str) or not label or "/" in label or label != label.strip():
            raise LabelClashError(
                f"{self.kind} {where}: state label {label!r} must be a non-empty name "
                "without '/' or surrounding blanks",
                where,
                str(label),
                label,
                "label",
            )
        if label in self._children:
            raise LabelClashError(
                f"{self.kind} {where}: state label {label!r} is used twice (labels: {_listed(list(self._children))})",
                where,
                label,
                label,
                "label",
            )
        if not isinstance(state, State):
            raise BehaviorConstructionError(
                f"{self.kind} {where}: {label!r} must be a State instance, got {type(state).__name__}",
                where,
                label,
                None,
                "state",
            )
        if state._parent is not None:
            raise BehaviorConstructionError(
                f"{self.kind} {where}: state instance for {label!r} was already added as {state._label!r} "
                f"to another container; build one instance per place",
                where,
                label,
                None,
                "state",
            )
        declared = (*state.input_keys, *(k for k in state.output_keys if k not in state.input_keys))
        remap: Dict[str, str] = {}
        for key, target in (remapping or {}).items():
            if key not in declared:
                raise UndeclaredKeyError(
                    f"{self.kind} {where}: remapping of {label!r} names key {key!r} that "
                    f"{type(state).__name__} does not declare (valid: {_listed(declared)})",
                    where,
                    label,
                    key,
                    "remapping",
                )
            if not isinstance(target, str) or not target:
                raise UndeclaredKeyError(
                    f"{self.kind} {where}: remapping of {label!r} maps {key!r} to {target!r}, not a key name",
                    where,
                    label,
                    key,
                    "remapping",
                )
            remap[key] = target
        levels: Dict[str, int] = {}
        for outcome, level in (autonomy or {}).items():
            if outcome not in state.outcomes:
                raise UnregisteredOutcomeError(
                    f"{self.kind} {where}: autonomy of {label!r} names outcome {outcome!r} that "
                    f"{type(state).__name__} does not register (valid: {_listed(state.outcomes)})",
                    where,
                    label,
                    outcome,
                    "autonomy",
                )
            try:
                levels[outcome] = int(Autonomy.parse(level))
            except ConfigError as err:
                raise BehaviorConstructionError(
                    f"{self.kind} {where}: autonomy of {label!r} for {outcome!r}: {err}",
                    where,
                    label,
                    outcome,
                    "autonomy",
                ) from err
        state._parent = self
        state._label = label
        self._children[label] = state
        self._remapping[label] = remap
        self._autonomy[label] = levels

    # --- introspection -----------------------------------------------------------------------------
    @property
    def children(self) -> Mapping[str, State]:
        """Children by label, in the order they were added."""
        return dict(self._children)

    def __getitem__(self, label: str) -> State:
        try:
            return self._children[label]
        except KeyError:
            what = f"{self.kind} {self._path or ''} has no state"
            raise KeyError(choices_message(what, label, self._children)) from None

    def remapping_of(self, label: str) -> Dict[str, str]:
        return dict(self._remapping[label])

    def autonomy_of(self, label: str) -> Dict[str, Autonomy]:
        """Required autonomy per outcome of child ``label`` (outcomes not listed: OFF)."""
        levels = self._autonomy[label]
        return {o: Autonomy(levels.get(o, 0)) for o in self._children[label].outcomes}

    @property
    def userdata_defaults(self) -> Dict[str, Any]:
        return dict(self._defaults)

    # --- validation ----------------------------------------------------------------------------------
    def validate(self) -> None:
        """Check the whole tree below this container; raise the first BehaviorConstructionError."""
        self._validate(self._path or "/")

    def _validate(self, path: str) -> None:
        raise NotImplementedError

    def _validate_children(self, path: str) -> None:
        for label, child in self._children.items():
            if isinstance(child, Container):
                child._validate(child_path(path, label))

    def _validate_keys(self, path: str) -> None:
        """Inputs of children must be provided; outputs of the container must be produced."""
        provided: Dict[str, str] = {k: "input of the container" for k in self._input_keys}
        provided.update({k: "userdata default" for k in self._defaults if k not in provided})
        for label, child in self._children.items():
            remap = self._remapping[label]
            for key in child.output_keys:
                provided.setdefault(remap.get(key, key), f"output of {label}")
        for label, child in self._children.items():
            remap = self._remapping[label]
            for key in child.input_keys:
                ckey = remap.get(key, key)
                if ckey not in provided:
                    renamed = f" (remapped to {ckey!r})" if ckey != key else ""
                    raise UndeclaredKeyError(
                        f"{self.kind} {path}: input key {key!r}{renamed} of state {label!r} is neither an input "
                        f"key nor a userdata default of the container nor an output of any of its states "
                        f"(available: {_listed(sorted(provided))})",
                        path,
                        label,
                        key,
                        "key",
                    )
        for key in self._output_keys:
            if key not in provided:
                raise UndeclaredKeyError(
                    f"{self.kind} {path}: output key {key!r} is produced by no state and is neither an input "
                    f"key nor a userdata default (available: {_listed(sorted(provided))})",
                    path,
                    None,
                    key,
                    "key",
                )

    # --- attaching to a behavior ---------------------------------------------------------------------------
    def _attach(self, ctx: Any, path: str, ancestors: FrozenSet[State]) -> None:
        super()._attach(ctx, path, ancestors)
        view = self._ud
        # keys that must stay read-only inside: our input-only keys, and keys protected above us
        self._protected = frozenset(k for k, (_, wrap) in view._ud_read.items() if wrap) if view else frozenset()
        self._data = {}
        below = ancestors | {self}
        for label, child in self._children.items():
            child._ud = self._make_view(child, self._remapping[label])
            child._routes = self._make_routes(label, child)
            child._attach(ctx, child_path(path, label), below)

    def _make_view(self, child: State, remap: Mapping[str, str]) -> UserDataView:
        read: ReadSpec = {}
        outputs = set(child.output_keys)
        for key in child.input_keys:
            ckey = remap.get(key, key)
            read[key] = (ckey, key not in outputs or ckey in self._protected)
        write = {key: remap.get(key, key) for key in child.output_keys}
        return UserDataView(self._data, read, write, child)

    def _make_routes(self, label: str, child: State) -> Dict[str, Route]:
        levels = self._autonomy[label]
        return {o: Route(None, None, levels.get(o, 0), "", "") for o in child.outcomes}

    # --- running -----------------------------------------------------------------------------------------
    def execute(self, userdata: UserDataView) -> Optional[str]:
        raise BehaviorRuntimeError(f"{self.kind} {self._path}: containers are run by the engine, not executed")

    def _activate(self, now: float) -> None:
        data = self._data
        data.clear()
        data.update(self._defaults)
        view = self._ud
        store = view._ud_store
        for key, (store_key, _) in view._ud_read.items():
            try:
                data[key] = store[store_key]
            except KeyError:
                if key in self._defaults:  # not provided: the default stands
                    continue
                renamed = f" (key {store_key!r} there)" if store_key != key else ""
                raise UserDataKeyError(
                    f"{self.kind} {self._path}: input key {key!r} has no value in its parent{renamed} "
                    f"(keys with a value: {_listed(sorted(store))})"
                ) from None
        self._active = True
        self._entering = False
        self._entered = True
        self._due = now

    def _write_outputs(self) -> None:
        view = self._ud
        store = view._ud_store
        data = self._data
        for key, store_key in view._ud_write.items():
            if key in data:  # an output nobody wrote (e.g. on a failure path) stays unset above
                store[store_key] = data[key]

    def _leave(self) -> None:
        """Finished with an outcome that fired: hand the outputs to the parent."""
        self._active = False
        self._entered = False
        self._due = math.inf
        if self._pending is not None:
            self._drop_pending()
        self._write_outputs()

    def _abort(self) -> None:
        """Exit every active child (deepest first), without writing outputs."""
        for child in self._active_children():
            child._abort()
        self._active = False
        self._entered = False
        self._due = math.inf
        if self._pending is not None:
            self._drop_pending()

    def _active_children(self) -> List[State]:
        raise NotImplementedError

    def _walk(self) -> Iterator[State]:
        yield self
        for child in self._children.values():
            yield from child._walk()

    def _active_leaves(self) -> Iterator[State]:
        for child in self._active_children():
            yield from child._active_leaves()

    def _active_paths(self) -> Iterator[str]:
        if not self._active:
            return
        children = self._active_children()
        if not children:  # finished, its outcome waits in the parent
            yield self._path
        for child in children:
            yield from child._active_paths()

    # --- gating of child outcomes (slow paths) -------------------------------------------------------------
    def _route(self, child: State, outcome: object) -> Route:
        try:
            return child._routes[outcome]  # type: ignore[index]
        except (KeyError, TypeError):
            raise BehaviorRuntimeError(
                f"state {child._path!r} ({type(child).__name__}) returned outcome {outcome!r} which it does not "
                f"register (valid: {_listed(child.outcomes)}; None keeps it running)"
            ) from None

    def _must_wait(self, child: State, outcome: str, route: Route, by_operator: bool, now: float) -> bool:
        """Lock or autonomy says ``outcome`` of ``child`` cannot fire now: mark it pending and say so."""
        ctx = self._ctx
        assert ctx is not None
        if ctx._lock_count and self._leaves_locked(child, route):
            wait = PendingReason.LOCK
        elif not by_operator and ctx._gate and route.required >= ctx._autonomy:
            wait = PendingReason.AUTONOMY
        else:
            return False
        pending = child._pending
        if pending is None:
            pending = Pending(outcome, wait, route.required)
            child._pending = pending
        elif pending.outcome != outcome or pending.announced is not wait:
            if pending.announced is not None:  # withdraw what the operator saw before saying the new reason
                ctx._emit_request(now, child._path, pending.outcome, pending.required, pending.announced, False)
                pending.announced = None
            pending.outcome, pending.required = outcome, route.required
            if pending.reason is not PendingReason.FORCED:  # a forced outcome stays forced while a lock holds it
                pending.reason = wait
        ctx._requests[child._path] = child
        if pending.announced is None:
            pending.announced = wait
            ctx._emit_request(now, child._path, outcome, route.required, wait, True)
        child._due = math.inf
        return True

    def _resolve(self, child: State, now: float) -> Optional[Tuple[str, Route, bool]]:
        """A child with a pending outcome was woken: (outcome, route, by operator) if it fires now.

        The child is exited here: aborted if the operator forced the outcome, left normally otherwise.
        """
        pending = child._pending
        assert pending is not None
        route = child._routes[pending.outcome]
        forced = pending.reason is PendingReason.FORCED
        by_operator = forced or pending.approved
        if self._must_wait(child, pending.outcome, route, by_operator, now):
            return None
        child._drop_pending()
        if forced:
            child._abort()
        else:
            child._leave()
        return pending.outcome, route, by_operator

    def _leaves_locked(self, child: State, route: Route) -> bool:
        """Would firing ``route`` of ``child`` leave a locked state or container?"""
        if child._locked:
            return True
        node: Optional[State] = self
        outcome = route.container_outcome
        while outcome is not None and node is not None:  # the transition leaves ``node``
            if node._locked:
                return True
            parent = node._parent
            if parent is None:
                return False
            outcome = node._routes[outcome].container_outcome if outcome in node._routes else None
            node = parent
        return False
