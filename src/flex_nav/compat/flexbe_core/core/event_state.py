"""FlexBE's EventState as a flex_nav state: same constructor keywords, same lifecycle hooks.

A FlexBE state library subclasses ``EventState``::

    class WaitState(EventState):
        def __init__(self, wait_time):
            super(WaitState, self).__init__(outcomes=['done'])
            self._wait_time = wait_time
        def on_enter(self, userdata): ...
        def execute(self, userdata): return 'done' if ... else None

The hooks are flex_nav's (and FlexBE's): ``on_start()``, ``on_enter(userdata)``,
``execute(userdata)`` (an outcome, or None to keep running; never blocking), ``on_exit(userdata)``,
``on_pause()``, ``on_resume(userdata)``, ``on_stop()``, so the engine calls them directly (no method
swapping). ``io_keys`` are both input and output keys; repeated outcomes or keys are merged, as
FlexBE does. The execution rate is 10 Hz unless ``set_rate(hz)`` says otherwise. Proxies created in
``__init__`` belong to the behavior being built (see :mod:`flex_nav.compat.flexbe_core.proxy.hub`).
"""

from __future__ import annotations

from typing import Iterable

from flex_nav.behavior.state import State
from flex_nav.exceptions import ConfigError


def _merged(*groups: Iterable[str]) -> list[str]:
    return list(dict.fromkeys(name for group in groups for name in group))


class EventState(State):
    """Base class of FlexBE states (flexbe_core 1.x's constructor, flex_nav's engine)."""

    def __init__(
        self,
        outcomes: Iterable[str] = (),
        input_keys: Iterable[str] = (),
        output_keys: Iterable[str] = (),
        io_keys: Iterable[str] = (),
    ) -> None:
        given = (("outcomes", outcomes), ("input_keys", input_keys), ("output_keys", output_keys), ("io_keys", io_keys))
        for what, values in given:
            if isinstance(values, str):  # merging would split the string into letters
                raise ConfigError(f"{type(self).__name__}: {what} must be a list of names, not the string {values!r}")
        super().__init__(
            outcomes=_merged(outcomes),
            input_keys=_merged(input_keys, io_keys),
            output_keys=_merged(output_keys, io_keys),
        )

    def set_rate(self, rate: float) -> None:
        """Execute this state at ``rate`` [Hz] while it is active."""
        self.rate_hz = rate

    @property
    def sleep_duration(self) -> float:
        """[s] time between two executions of this state."""
        return 1.0 / self.rate_hz


__all__ = ["EventState"]
