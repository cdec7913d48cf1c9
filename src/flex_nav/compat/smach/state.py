"""SMACH's leaf states: :class:`State` (blocking ``execute(ud)`` returning an outcome) and :class:`CBState`.

A SMACH state declares its outcomes and the userdata keys it reads (``input_keys``), writes
(``output_keys``) or both (``io_keys``), and runs to completion in ``execute(ud)``. Preemption is
cooperative: a container (or another thread) calls :meth:`State.request_preempt`; the state notices
``preempt_requested()``, calls ``service_preempt()`` and returns (by convention ``'preempted'``).
``recall_preempt()`` withdraws a request that was not serviced.

Outcomes and keys are kept in registration order (SMACH keeps sets); the ``_outcomes``,
``_input_keys`` and ``_output_keys`` attributes stay sets, as code written for SMACH may read them.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Set, Tuple

from flex_nav.compat.smach.util import has_smach_interface, names
from flex_nav.exceptions import InvalidStateError


class State:
    """Base class of SMACH states: override ``execute(ud)`` and return one of the registered outcomes."""

    def __init__(
        self,
        outcomes: Iterable[str] = (),
        input_keys: Iterable[str] = (),
        output_keys: Iterable[str] = (),
        io_keys: Iterable[str] = (),
    ) -> None:
        self._outcomes: Set[str] = set()
        self._input_keys: Set[str] = set()
        self._output_keys: Set[str] = set()
        self._order: Dict[str, List[str]] = {"outcomes": [], "input_keys": [], "output_keys": []}
        self._cache: Dict[str, Tuple[str, ...]] = {}  # registered names in order (hot path of containers)
        self._preempt_requested = False
        self._shutdown_requested = False
        self.register_outcomes(outcomes)
        self.register_input_keys(input_keys)
        self.register_output_keys(output_keys)
        self.register_io_keys(io_keys)

    # --- meat ---------------------------------------------------------------------------------
    def execute(self, ud: Any) -> Optional[str]:
        """Run the state (blocking) and return one of its registered outcomes."""
        raise NotImplementedError(f"{type(self).__name__} must implement execute(ud)")

    # --- interface declaration -------------------------------------------------------------------
    def _register(self, what: str, target: Set[str], values: Iterable[str]) -> None:
        added = names(what, values, type(self).__name__)
        order = self._order[what]
        for value in added:
            if value not in target:
                target.add(value)
                order.append(value)
        self._cache.pop(what, None)

    def _ordered(self, what: str, current: Set[str]) -> Tuple[str, ...]:
        cached = self._cache.get(what)
        if cached is not None and len(cached) == len(current):  # the sets may be changed behind our back
            return cached
        order = self._order[what]
        listed = tuple(v for v in order if v in current)
        if len(listed) != len(current):
            listed += tuple(sorted(current.difference(order)))
        self._cache[what] = listed
        return listed

    def register_outcomes(self, new_outcomes: Iterable[str]) -> None:
        """Add outcomes to the registered ones."""
        self._register("outcomes", self._outcomes, new_outcomes)

    def get_registered_outcomes(self) -> Tuple[str, ...]:
        return self._ordered("outcomes", self._outcomes)

    def register_io_keys(self, keys: Iterable[str]) -> None:
        """Add keys the state may both read and write."""
        keys = names("io_keys", keys, type(self).__name__)
        self.register_input_keys(keys)
        self.register_output_keys(keys)

    def register_input_keys(self, keys: Iterable[str]) -> None:
        self._register("input_keys", self._input_keys, keys)

    def get_registered_input_keys(self) -> Tuple[str, ...]:
        return self._ordered("input_keys", self._input_keys)

    def register_output_keys(self, keys: Iterable[str]) -> None:
        self._register("output_keys", self._output_keys, keys)

    def get_registered_output_keys(self) -> Tuple[str, ...]:
        return self._ordered("output_keys", self._output_keys)

    # --- preemption -------------------------------------------------------------------------------
    def request_preempt(self) -> None:
        """Ask the state to stop; it should notice ``preempt_requested()`` and return soon."""
        self._preempt_requested = True

    def service_preempt(self) -> None:
        """The state acknowledges the request (call it before returning because of a preempt)."""
        self._preempt_requested = False

    def recall_preempt(self) -> None:
        """Withdraw a request that was not serviced."""
        self._preempt_requested = False

    def preempt_requested(self) -> bool:
        return self._preempt_requested

    def request_shutdown(self) -> None:
        """SMACH's shutdown hook: remember it and preempt."""
        self._shutdown_requested = True
        self.request_preempt()


class CBState(State):
    """A state made of one callback: ``execute(ud)`` returns ``cb(ud, *cb_args, **cb_kwargs)``.

    If the callback was decorated with :func:`~flex_nav.compat.smach.util.cb_interface`, its declared
    outcomes and keys are added to the state's.
    """

    def __init__(  # noqa: PLR0917  (SMACH's signature)
        self,
        cb: Callable[..., Optional[str]],
        cb_args: Sequence[Any] = (),
        cb_kwargs: Optional[Dict[str, Any]] = None,
        outcomes: Iterable[str] = (),
        input_keys: Iterable[str] = (),
        output_keys: Iterable[str] = (),
        io_keys: Iterable[str] = (),
    ) -> None:
        if not callable(cb):
            raise InvalidStateError(f"CBState needs a callable, got {cb!r}")
        super().__init__(outcomes, input_keys, output_keys, io_keys)
        self._cb = cb
        self._cb_args = tuple(cb_args)
        self._cb_kwargs = dict(cb_kwargs or {})
        if has_smach_interface(cb):
            self.register_input_keys(cb.get_registered_input_keys())  # type: ignore[attr-defined]
            self.register_output_keys(cb.get_registered_output_keys())  # type: ignore[attr-defined]
            self.register_outcomes(cb.get_registered_outcomes())  # type: ignore[attr-defined]

    def execute(self, ud: Any) -> Optional[str]:
        return self._cb(ud, *self._cb_args, **self._cb_kwargs)


__all__ = ["CBState", "State"]
