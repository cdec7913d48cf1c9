"""WaitState: wait for a time on the behavior's clock."""

from __future__ import annotations

from flex_nav.behavior.builtin_states import Wait


class WaitState(Wait):
    """Waits until a time has passed on the behavior's clock (simulated time in a simulation); never blocks.

    -- wait_time_s  float  [s] How long to wait after entering (>= 0).

    <= done  The time has passed.
    """
