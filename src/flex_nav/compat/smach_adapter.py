"""SmachStateAdapter: a SMACH state (or container) used as a state of a flex_nav behavior.

flex_nav's engine never blocks: ``execute`` is polled and returns None while a state works. A SMACH
state blocks in its ``execute(ud)`` until it is done. The adapter bridges the two with ONE worker
thread per activation (started in ``on_enter``, never per tick)::

    sm.add("Legacy", SmachStateAdapter(LegacySmachState()), transitions={"succeeded": "Next", ...})

- ``on_enter``: the declared input keys are read from flex_nav's userdata into a private SMACH
  :class:`~flex_nav.compat.smach.user_data.UserData` (input-only values stay read-only views), and the
  worker thread runs ``smach_state.execute(Remapper(...))`` on it.
- ``execute``: None while the thread runs; then the SMACH state's output keys are written back and
  its outcome returned (an unregistered one raises :class:`InvalidTransitionError`; an exception in the
  SMACH state raises :class:`InvalidUserCodeError`, which fails the behavior). Outputs are written only
  when the state finishes normally, from the engine's thread, so a preempted state changes nothing.
- ``on_exit`` while the thread still runs (preempt, forced transition, end of a concurrency
  container, failure elsewhere): ``request_preempt()`` on the SMACH state, then a bounded wait
  (``stop_timeout_s``) for it to return; if it does not, :class:`BehaviorRuntimeError` names it (the
  daemon thread cannot be killed and is left behind; the behavior fails loudly).

Pause does not stop a running SMACH state (SMACH has no pause); the outcome is taken after resume.
The outcome is noticed at the adapter's ``rate_hz`` (default 20 Hz).
"""

from __future__ import annotations

import threading
from typing import Any, Optional

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.compat.smach.user_data import Remapper, UserData
from flex_nav.compat.smach.util import has_smach_interface
from flex_nav.exceptions import (
    BehaviorRuntimeError,
    ConfigError,
    InvalidTransitionError,
    InvalidUserCodeError,
    SmachError,
)

DEFAULT_ADAPTER_RATE_HZ = 20.0  # [Hz] how often the adapter checks whether the SMACH state has returned
DEFAULT_STOP_TIMEOUT_S = 5.0  # [s] how long a preempted SMACH state may take to return


class SmachStateAdapter(State):
    """Runs a blocking SMACH state in a worker thread (one per activation) inside a flex_nav behavior."""

    def __init__(
        self,
        smach_state: Any,
        rate_hz: float = DEFAULT_ADAPTER_RATE_HZ,
        stop_timeout_s: float = DEFAULT_STOP_TIMEOUT_S,
    ) -> None:
        if not (has_smach_interface(smach_state) and callable(getattr(smach_state, "execute", None))):
            raise ConfigError(
                f"SmachStateAdapter needs a SMACH state (execute, get_registered_outcomes/input_keys/output_keys), "
                f"got {type(smach_state).__name__}"
            )
        if not stop_timeout_s > 0.0:
            raise ConfigError(f"SmachStateAdapter: stop_timeout_s must be > 0 [s], got {stop_timeout_s!r}")
        super().__init__(
            outcomes=list(smach_state.get_registered_outcomes()),
            input_keys=list(smach_state.get_registered_input_keys()),
            output_keys=list(smach_state.get_registered_output_keys()),
            rate_hz=rate_hz,
        )
        self.smach_state = smach_state
        self._stop_timeout_s = float(stop_timeout_s)
        self._thread: Optional[threading.Thread] = None
        self._done = threading.Event()
        self._local = UserData()
        self._outcome: Any = None
        self._error: Optional[BaseException] = None

    def on_enter(self, userdata: UserDataView) -> None:
        local = UserData()
        for key in self.input_keys:
            if key in userdata:
                local[key] = userdata[key]
        self._local = local
        self._outcome = None
        self._error = None
        self._done = threading.Event()
        self.smach_state.recall_preempt()  # a stale request of an earlier activation must not stop this one
        self._thread = threading.Thread(
            target=self._run, args=(local, self._done), name=f"smach_adapter:{self.path}", daemon=True
        )
        self._thread.start()

    def _run(self, local: UserData, done: threading.Event) -> None:
        state = self.smach_state
        try:
            self._outcome = state.execute(
                Remapper(local, state.get_registered_input_keys(), state.get_registered_output_keys())
            )
        except BaseException as err:
            self._error = err
        finally:
            done.set()

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if not self._done.is_set():
            return None
        if self._thread is not None:
            self._thread.join()
            self._thread = None
        error = self._error
        if error is not None:
            if isinstance(error, SmachError):
                raise error
            raise InvalidUserCodeError(
                f"SMACH state {type(self.smach_state).__name__} at {self.path!r} raised {type(error).__name__}: {error}"
            ) from error
        outcome = self._outcome
        if outcome not in self.outcomes:
            raise InvalidTransitionError(
                f"SMACH state {type(self.smach_state).__name__} at {self.path!r} returned outcome {outcome!r}, "
                f"which it does not register (registered: {', '.join(self.outcomes)})"
            )
        local = self._local
        for key in self.output_keys:
            if key in local:
                userdata[key] = local[key]
        return str(outcome)

    def on_exit(self, userdata: UserDataView) -> None:
        thread = self._thread
        if thread is None:
            return
        if not self._done.is_set():
            self.smach_state.request_preempt()
            if not self._done.wait(self._stop_timeout_s):
                raise BehaviorRuntimeError(
                    f"SMACH state {type(self.smach_state).__name__} at {self.path!r} did not return within "
                    f"{self._stop_timeout_s} s of its preempt request"
                )
        thread.join()
        self._thread = None


__all__ = ["SmachStateAdapter"]
