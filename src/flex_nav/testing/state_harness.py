"""Run one state (or a whole machine) without ROS: the behavior executor on a ManualClock with fake proxies.

:class:`StateHarness` makes the root of a behavior out of a state, with a
:class:`~flex_nav.behavior.ManualClock` and :class:`~flex_nav.testing.fake_proxies.FakeProxies` on that clock,
and records the behavior's log events. The test injects messages (``harness.proxies.sub(topic).inject``),
scripts action servers (``harness.proxies.client(name, type).respond(...)``), moves time and ticks
(``advance``, ``tick``, ``run``, ``run_for``) and reads what was published (``harness.proxies.pub(topic)``).
Something that moves with time (a simulated robot turning published twists into odometry) can be attached
as ``harness.robot``: :meth:`StateHarness.advance` steps it. See :mod:`flex_nav.testing.fake_proxies` for an
example. Nothing here imports rospy.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Protocol

from flex_nav.behavior import BehaviorExecutor, BehaviorResult, LogEvent, ManualClock, State
from flex_nav.testing.fake_proxies import FakeProxies

START_S = 1000.0  # [s] clock start: stamps are clearly non-zero
DEFAULT_STEP_S = 0.05  # [s] time step of run() when the behavior is not due at a known time, and of run_for()


class Steppable(Protocol):
    """Something the harness moves along with time (e.g. a simulated robot)."""

    def step(self, dt_s: float) -> None: ...


class StateHarness:
    """One state (or machine) as the root of a behavior, with its clock, fake proxies and recorded logs.

    ``executor_kwargs`` go to :class:`~flex_nav.behavior.BehaviorExecutor` (``autonomy``, ``supervised``...).
    """

    def __init__(self, root: State, inputs: Optional[Dict[str, Any]] = None, **executor_kwargs: Any) -> None:
        self.clock = ManualClock(START_S)
        self.proxies = FakeProxies(self.clock)
        self.root = root
        self.executor = BehaviorExecutor(root, inputs=inputs, clock=self.clock, proxies=self.proxies,
                                         **executor_kwargs)
        self.logs: List[LogEvent] = []
        self.executor.context.hooks.log.append(self.logs.append)
        self.robot: Optional[Steppable] = None

    def start(self) -> StateHarness:
        self.executor.start()
        return self

    def tick(self) -> bool:
        """Run one due tick (applying commands first); True if the behavior ended."""
        self.executor.spin_once()
        return self.executor.status.is_terminal

    def advance(self, dt_s: float) -> None:
        """Move time on by ``dt_s`` [s]; the robot (if any) is stepped for that long."""
        self.clock.advance(dt_s)
        if self.robot is not None:
            self.robot.step(dt_s)

    def run(self, max_time_s: float = 60.0, step_s: Optional[float] = None) -> BehaviorResult:
        """Tick at the root's due times (or every ``step_s`` [s]) until the behavior ends; AssertionError if it
        has not ended after ``max_time_s`` [s]."""
        end = self.clock.now() + max_time_s
        while self.clock.now() <= end:
            if self.tick():
                return self.executor.result()
            due = self.executor.due_s
            if step_s is not None:
                dt = step_s
            else:
                dt = due - self.clock.now() if math.isfinite(due) and due > self.clock.now() else DEFAULT_STEP_S
            self.advance(dt)
        raise AssertionError(f"behavior still {self.executor.status.value} after {max_time_s} s; logs: {self.texts()}")

    def run_for(self, duration_s: float, step_s: float = DEFAULT_STEP_S) -> None:
        """Tick every ``step_s`` [s] for ``duration_s`` [s]; AssertionError if the behavior ends meanwhile."""
        end = self.clock.now() + duration_s - 1e-9
        while self.clock.now() < end:
            if self.tick():
                raise AssertionError(f"ended early: {self.executor.result()}; logs: {self.texts()}")
            self.advance(step_s)

    def texts(self, min_level: int = 0) -> List[str]:
        """The messages logged at ``min_level`` (a LogLevel value) or above."""
        return [e.message for e in self.logs if int(e.level) >= min_level]

    def log_text(self) -> str:
        return "\n".join(f"{e.level.name}: {e.message}" for e in self.logs)


__all__ = ["START_S", "StateHarness", "Steppable"]
