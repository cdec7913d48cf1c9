"""The common part of the motion states: velocity commands out, odometry in, zero twist on every exit.

:class:`MotionBase` publishes geometry_msgs/TwistStamped on ``cmd_topic`` (default ``cmd_vel_stamped``; a
``twist_relay`` turns it into the base's Twist) and reads nav_msgs/Odometry on ``odom_topic`` (the groups
:class:`~flex_nav_states.motion_params.CommandOutput` and :class:`~flex_nav_states.motion_params.OdometryInput`,
which a subclass builds from its flat parameters). Its guarantees, whatever the subclass does:

- a zero twist is published in ``on_exit`` (own outcome, preemption, a monitor ending the concurrency,
  a forced transition, a failure elsewhere) and in ``on_pause``;
- odometry counts only while fresh (age <= ``odom_timeout_s`` by header stamp on the behavior's clock,
  or by arrival time when unstamped); :meth:`odometry_lost` says when none was fresh for longer than that;
- :meth:`elapsed_s` is the time since entry without the time spent paused, for timeouts.

:class:`StallWatch` detects "no progress for a window" for the closed-loop states.
"""

from __future__ import annotations

import math
from typing import Optional, Sequence

from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav_states import validation
from flex_nav_states.messages import OdomSample, message_age_s, odom_sample, sample_is_finite, twist_stamped
from flex_nav_states.motion_params import CommandOutput, OdometryInput
from flex_nav_states.proxy_types import PublisherLike, SubscriptionLike, proxies_of

MOTION_RATE_HZ = 20.0  # [Hz] default rate of the motion states (a twist_relay times out after 0.5 s)
AUTO_TIMEOUT_FACTOR = 2.0  # timeout_s 0: this many times the nominal duration ...
AUTO_TIMEOUT_MARGIN_S = 2.0  # [s] ... plus this margin


class StallWatch:
    """True when a monotone progress measure has not grown by ``min_progress`` within ``window_s`` [s]."""

    def __init__(self, window_s: float, min_progress: float) -> None:
        self.window_s = window_s
        self.min_progress = min_progress
        self._best = 0.0
        self._since_s = 0.0

    def reset(self, progress: float, now_s: float) -> None:
        self._best = progress
        self._since_s = now_s

    def restart_window(self, now_s: float) -> None:
        """Keep the best progress but start the window again (e.g. after a pause)."""
        self._since_s = now_s

    def stalled(self, progress: float, now_s: float) -> bool:
        if progress >= self._best + self.min_progress:
            self._best = progress
            self._since_s = now_s
            return False
        return now_s - self._since_s > self.window_s

    @property
    def best(self) -> float:
        return self._best


def closed_loop_timeout(owner: str, timeout_s: float, *, amount: float, amount_name: str, speed: float,
                        speed_name: str) -> float:
    """[s] The timeout of a closed-loop move of ``amount`` at ``speed``: ``timeout_s``, or when 0 twice the nominal
    duration plus a margin; ConfigError when it is shorter than the nominal duration."""
    timeout = validation.number(owner, "timeout_s", timeout_s, minimum=0.0, unit="[s]")
    nominal_s = abs(amount) / speed
    if timeout == 0.0:
        return AUTO_TIMEOUT_FACTOR * nominal_s + AUTO_TIMEOUT_MARGIN_S
    if timeout < nominal_s:
        raise ConfigError(
            f"{owner}: timeout_s {timeout:g} s is shorter than |{amount_name}| / {speed_name} = {nominal_s:.2f} s"
        )
    return timeout


def stall_watch(owner: str, stall_window_s: float, *, progress_name: str, min_progress: float, unit: str,
                slowest_speed: float) -> StallWatch:
    """A StallWatch for ``min_progress`` [unit] per ``stall_window_s`` [s]; ConfigError when that progress cannot be
    made in the window at ``slowest_speed`` [unit/s] (the watch would fire on a robot that moves as told)."""
    window = validation.number(owner, "stall_window_s", stall_window_s, positive=True, unit="[s]")
    least = validation.number(owner, progress_name, min_progress, positive=True, unit=f"[{unit}]")
    if least >= slowest_speed * window:
        raise ConfigError(
            f"{owner}: {progress_name} {least:g} {unit} cannot be made in stall_window_s {window:g} s at the "
            f"slowest commanded speed {slowest_speed:g} {unit}/s; lower it below {slowest_speed * window:g} {unit}"
        )
    return StallWatch(window, least)


class MotionBase(State):
    """Base of the motion states (not a state by itself; see the module docstring)."""

    def __init__(
        self,
        outcomes: Sequence[str],
        *,
        command: CommandOutput,
        odometry: Optional[OdometryInput],
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
    ) -> None:
        """``command``: where the commands go; ``odometry``: where odometry comes from (None: the state reads none)."""
        super().__init__(outcomes=outcomes, input_keys=input_keys, output_keys=output_keys, rate_hz=MOTION_RATE_HZ)
        self._command_output = command
        self._odometry_input = odometry
        self._cmd: Optional[PublisherLike] = None
        self._odom: Optional[SubscriptionLike] = None
        self._enter_s = 0.0
        self._paused_total_s = 0.0
        self._pause_start_s = 0.0
        self._last_fresh_s = 0.0  # [s] when a fresh odometry sample was last seen (entry counts as one)

    # --- lifecycle ---------------------------------------------------------------------------------
    def on_start(self) -> None:
        proxies = proxies_of(self)
        self._cmd = proxies.publisher(self._command_output.topic, TwistStamped)
        if self._odometry_input is not None:
            self._odom = proxies.subscription(self._odometry_input.topic, Odometry)

    def on_enter(self, userdata: UserDataView) -> None:
        now = self.now_s()
        self._enter_s = now
        self._paused_total_s = 0.0
        self._last_fresh_s = now

    def on_exit(self, userdata: UserDataView) -> None:
        self.stop()

    def on_pause(self) -> None:
        self.stop()
        self._pause_start_s = self.now_s()

    def on_resume(self, userdata: UserDataView) -> None:
        now = self.now_s()
        self._paused_total_s += now - self._pause_start_s
        self._last_fresh_s = now  # odometry gets its grace again

    # --- for subclasses ----------------------------------------------------------------------------
    def send(self, v: float, w: float) -> None:
        """Publish a velocity command: ``v`` [m/s] forward, ``w`` [rad/s] counter-clockwise."""
        if not (math.isfinite(v) and math.isfinite(w)):  # never send NaN to a base; stop loudly instead
            self.log_error(f"non-finite velocity command v={v!r} w={w!r} replaced by a stop")
            v = w = 0.0
        if self._cmd is None:
            self._cmd = proxies_of(self).publisher(self._command_output.topic, TwistStamped)
        self._cmd.publish(twist_stamped(v, w, self._command_output.frame_id, self.now_s()))

    def stop(self) -> None:
        self.send(0.0, 0.0)

    def elapsed_s(self) -> float:
        """[s] time since entry, without the paused time."""
        return self.now_s() - self._enter_s - self._paused_total_s

    def odometry_input(self) -> OdometryInput:
        """Where odometry comes from; ConfigError for a state built without odometry."""
        if self._odometry_input is None:
            raise ConfigError(f"{type(self).__name__}: needs odometry but odom_topic is empty")
        return self._odometry_input

    def odometry(self) -> Optional[OdomSample]:
        """The newest odometry sample if it is fresh and finite, else None."""
        odometry = self.odometry_input()
        sub = self._odom
        if sub is None:
            sub = self._odom = proxies_of(self).subscription(odometry.topic, Odometry)
        msg = sub.last()
        if msg is None:
            return None
        now = self.now_s()
        if message_age_s(msg, sub, now) > odometry.timeout_s:
            return None
        sample = odom_sample(msg)
        if not sample_is_finite(sample):
            return None
        self._last_fresh_s = now
        return sample

    def odometry_lost(self) -> bool:
        """True when no fresh odometry was seen for longer than odom_timeout_s (entry and resume count as seen)."""
        return self.now_s() - self._last_fresh_s > self.odometry_input().timeout_s

    def odometry_problem(self) -> str:
        odometry = self.odometry_input()
        sub = self._odom
        last = sub.last() if sub is not None else None
        if last is None:
            return f"no odometry on {odometry.topic} within odom_timeout_s {odometry.timeout_s:g} s"
        age = message_age_s(last, sub, self.now_s()) if sub is not None else math.inf
        return (
            f"odometry on {odometry.topic} is stale or invalid: newest is {age:.2f} s old "
            f"(odom_timeout_s {odometry.timeout_s:g} s)"
        )
