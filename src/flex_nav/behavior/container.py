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
from typing import TYPE_CHECKING, Any, Dict, FrozenSet, Iterator, List, Mapping, Optional, Sequence, Tuple

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.state import Pending, PendingReason, Route, State, StateRuntime
from flex_nav.behavior.userdata import ReadSpec, UserDataView, view_parts
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

if TYPE_CHECKING:
    from flex_nav.behavior.context import ContextRuntime


def child_path(parent_path: str, label: str) -> str:
    return f"{parent_path.rstrip('/')}/{label}"


def listed(values: Sequence[str] | FrozenSet[str]) -> str:
    """Names for a message: "a, b, c", or "none"."""
    return ", ".join(values) if values else "none"


class ContainerRuntime(StateRuntime):
    """The engine's record of a container: the calls the engine makes on every state's record reach
    the container here, which drives its children (their records) in its own methods."""

    __slots__ = ("container",)

    def __init__(self, container: Container, declared: StateRuntime) -> None:
        super().__init__(container, declared.outcomes, declared.input_keys, declared.output_keys, declared.period_s)
        self.container = container

    def copy_for(self, state: State) -> StateRuntime:
        assert isinstance(state, Container)
        twin = super().copy_for(state)
        assert isinstance(twin, ContainerRuntime)
        twin.container = state
        return twin

    def attach(self, ctx: ContextRuntime, path: str, ancestors: FrozenSet[StateRuntime]) -> None:
        super().attach(ctx, path, ancestors)
        self.container._attach_children(ctx, path, ancestors | {self})

    def walk(self) -> Iterator[StateRuntime]:
        yield self
        for child in self.container._children.values():
            yield from child.__flex_nav_runtime__.walk()

    def active_leaves(self) -> Iterator[StateRuntime]:
        for child in self.container._active_children():
            yield from child.active_leaves()

    def active_paths(self) -> Iterator[str]:
        if not self.active:
            return
        children = self.container._active_children()
        if not children:  # finished, its outcome waits in the parent
            yield self.path
        for child in children:
            yield from child.active_paths()

    def activate(self, now: float) -> None:
        self.container._activate(now)

    def tick(self, now: float) -> Optional[str]:
        return self.container._tick(now)

    def leave(self) -> None:
        self.container._leave()

    def abort(self) -> None:
        self.container._abort()

    def deactivate(self) -> None:
        """The container left or was aborted: not active, not entered, nothing due, no pending outcome."""
        self.active = False
        self.entered = False
        self.due = math.inf
        if self.pending is not None:
            self.drop_pending()


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
        # a container's record drives its children (replaces the leaf record State made)
        self.__flex_nav_runtime__: ContainerRuntime = ContainerRuntime(self, self.__flex_nav_runtime__)
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
        where = self.path or "(unattached)"
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
                f"{self.kind} {where}: state label {label!r} is used twice (labels: {listed(list(self._children))})",
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
        child = state.__flex_nav_runtime__
        if child.parent is not None:
            raise BehaviorConstructionError(
                f"{self.kind} {where}: state instance for {label!r} was already added as {child.label!r} "
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
                    f"{type(state).__name__} does not declare (valid: {listed(declared)})",
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
                    f"{type(state).__name__} does not register (valid: {listed(state.outcomes)})",
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
        child.parent = self.__flex_nav_runtime__
        child.label = label
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
            what = f"{self.kind} {self.path or ''} has no state"
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
        self._validate(self.path or "/")

    def _validate(self, path: str) -> None:
        raise NotImplementedError

    def _validate_children(self, path: str) -> None:
        for label, child in self._children.items():
            if isinstance(child, Container):
                child._validate(child_path(path, label))

    def _validate_keys(self, path: str) -> None:
        """Inputs of children must be provided; outputs of the container must be produced."""
        provided: Dict[str, str] = {k: "input of the container" for k in self.input_keys}
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
                        f"(available: {listed(sorted(provided))})",
                        path,
                        label,
                        key,
                        "key",
                    )
        for key in self.output_keys:
            if key not in provided:
                raise UndeclaredKeyError(
                    f"{self.kind} {path}: output key {key!r} is produced by no state and is neither an input "
                    f"key nor a userdata default (available: {listed(sorted(provided))})",
                    path,
                    None,
                    key,
                    "key",
                )

    # --- attaching to a behavior (called by the container's record) ------------------------------------
    def _attach_children(self, ctx: ContextRuntime, path: str, below: FrozenSet[StateRuntime]) -> None:
        view = self.__flex_nav_runtime__.ud
        # keys that must stay read-only inside: our input-only keys, and keys protected above us
        self._protected = frozenset(k for k, (_, wrap) in view_parts(view)[1].items() if wrap) if view else frozenset()
        self._data = {}
        for label, state in self._children.items():
            child = state.__flex_nav_runtime__
            child.ud = self._make_view(state, self._remapping[label])
            child.routes = self._make_routes(label, state)
            child.attach(ctx, child_path(path, label), below)

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

    # --- running (the engine's calls on the container's record land here) --------------------------------
    def execute(self, userdata: UserDataView) -> Optional[str]:
        raise BehaviorRuntimeError(f"{self.kind} {self.path}: containers are run by the engine, not executed")

    def _activate(self, now: float) -> None:
        rt = self.__flex_nav_runtime__
        data = self._data
        data.clear()
        data.update(self._defaults)
        store, read, _ = view_parts(rt.ud)
        for key, (store_key, _) in read.items():
            try:
                data[key] = store[store_key]
            except KeyError:
                if key in self._defaults:  # not provided: the default stands
                    continue
                renamed = f" (key {store_key!r} there)" if store_key != key else ""
                raise UserDataKeyError(
                    f"{self.kind} {rt.path}: input key {key!r} has no value in its parent{renamed} "
                    f"(keys with a value: {listed(sorted(store))})"
                ) from None
        rt.active = True
        rt.entering = False
        rt.entered = True
        rt.due = now

    def _write_outputs(self) -> None:
        store, _, write = view_parts(self.__flex_nav_runtime__.ud)
        data = self._data
        for key, store_key in write.items():
            if key in data:  # an output nobody wrote (e.g. on a failure path) stays unset above
                store[store_key] = data[key]

    def _leave(self) -> None:
        """Finished with an outcome that fired: hand the outputs to the parent."""
        self.__flex_nav_runtime__.deactivate()
        self._write_outputs()

    def _abort(self) -> None:
        """Exit every active child (deepest first), without writing outputs."""
        for child in self._active_children():
            child.abort()
        self.__flex_nav_runtime__.deactivate()

    def _tick(self, now: float) -> Optional[str]:
        raise NotImplementedError

    def _active_children(self) -> List[StateRuntime]:
        raise NotImplementedError

    # --- gating of child outcomes (slow paths) -------------------------------------------------------------
    def _route(self, child: StateRuntime, outcome: object) -> Route:
        try:
            return child.routes[outcome]  # type: ignore[index]
        except (KeyError, TypeError):
            raise BehaviorRuntimeError(
                f"state {child.path!r} ({type(child.state).__name__}) returned outcome {outcome!r} which it does not "
                f"register (valid: {listed(child.outcomes)}; None keeps it running)"
            ) from None

    def _must_wait(self, child: StateRuntime, outcome: str, route: Route, by_operator: bool, now: float) -> bool:
        """Lock or autonomy says ``outcome`` of ``child`` cannot fire now: mark it pending and say so."""
        ctx = child.ctx
        assert ctx is not None
        if ctx.lock_count and self._leaves_locked(child, route):
            wait = PendingReason.LOCK
        elif not by_operator and ctx.gate and route.required >= ctx.autonomy:
            wait = PendingReason.AUTONOMY
        else:
            return False
        pending = child.pending
        if pending is None:
            pending = Pending(outcome, wait, route.required)
            child.pending = pending
        elif pending.outcome != outcome or pending.announced is not wait:
            if pending.announced is not None:  # withdraw what the operator saw before saying the new reason
                ctx.emit_request(now, child.path, pending.outcome, pending.required, pending.announced, False)
                pending.announced = None
            pending.outcome, pending.required = outcome, route.required
            if pending.reason is not PendingReason.FORCED:  # a forced outcome stays forced while a lock holds it
                pending.reason = wait
        ctx.requests[child.path] = child
        if pending.announced is None:
            pending.announced = wait
            ctx.emit_request(now, child.path, outcome, route.required, wait, True)
        child.due = math.inf
        return True

    def _resolve(self, child: StateRuntime, now: float) -> Optional[Tuple[str, Route, bool]]:
        """A child with a pending outcome was woken: (outcome, route, by operator) if it fires now.

        The child is exited here: aborted if the operator forced the outcome, left normally otherwise.
        """
        pending = child.pending
        assert pending is not None
        route = child.routes[pending.outcome]
        forced = pending.reason is PendingReason.FORCED
        by_operator = forced or pending.approved
        if self._must_wait(child, pending.outcome, route, by_operator, now):
            return None
        child.drop_pending()
        if forced:
            child.abort()
        else:
            child.leave()
        return pending.outcome, route, by_operator

    def _leaves_locked(self, child: StateRuntime, route: Route) -> bool:
        """Would firing ``route`` of ``child`` leave a locked state or container?"""
        if child.locked:
            return True
        node: Optional[StateRuntime] = self.__flex_nav_runtime__
        outcome = route.container_outcome
        while outcome is not None and node is not None:  # the transition leaves ``node``
            if node.locked:
                return True
            parent = node.parent
            if parent is None:
                return False
            outcome = node.routes[outcome].container_outcome if outcome in node.routes else None
            node = parent
        return False
