"""Safety rules shared by the motion nodes: finite commands, fresh sensors, a stop after silence.

Times are plain seconds from one clock chosen by the caller (``rospy.get_time()`` in the nodes, so the
rules follow simulated time when ``use_sim_time`` is set); nothing here reads a clock itself.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Dict, Optional

from flex_nav.exceptions import ConfigError


def twist_problem(linear: Sequence[float], angular: Sequence[float]) -> Optional[str]:
    """Why a velocity command (linear x, y, z [m/s]; angular x, y, z [rad/s]) must not reach a base, or None."""
    values = (*linear, *angular)
    if all(math.isfinite(v) for v in values):
        return None
    return (f"non-finite velocity command linear=({', '.join(f'{v:g}' for v in linear)}) "
            f"angular=({', '.join(f'{v:g}' for v in angular)})")


class CommandTimeout:
    """When a relay must send one zero command: ``timeout_s`` [s] after the last command, once.

    ``timeout_s`` 0 disables it. After the zero went out nothing more is due until a new command arrives,
    so a stopped robot is not flooded with zeros.
    """

    def __init__(self, timeout_s: float) -> None:
        if not math.isfinite(timeout_s) or timeout_s < 0.0:
            raise ConfigError(f"command timeout must be a finite number >= 0 [s], got {timeout_s!r}")
        self.timeout_s = timeout_s
        self._last_command_s: Optional[float] = None

    def command(self, now_s: float) -> None:
        """A command was forwarded at ``now_s``."""
        self._last_command_s = now_s

    def stopped(self) -> None:
        """A zero command went out for another reason: nothing is due until the next command."""
        self._last_command_s = None

    def due(self, now_s: float) -> bool:
        """True exactly once per silence of at least ``timeout_s`` after a command; also once when the clock
        went back before the last command (a restarted simulation or a looped bag: its age is unknown)."""
        if self.timeout_s == 0.0 or self._last_command_s is None:
            return False
        if 0.0 <= now_s - self._last_command_s < self.timeout_s:
            return False
        self._last_command_s = None
        return True


class CommandOrder:
    """Keeps a relay fed by several publishers from forwarding a command older than one it already forwarded.

    Messages from different nodes have no order between them: a controller's last driving command can reach
    the relay after the stop a behavior state published when it took over, and would set the robot moving
    again. Commands carry their stamp [s]; one stamped before the newest forwarded command is stale, and at
    equal stamps a stop wins over motion. Stamp 0 (unstamped) is always forwarded and changes nothing.
    """

    def __init__(self) -> None:
        self._newest_s = -math.inf  # [s] stamp of the newest forwarded command
        self._newest_was_stop = False

    def reset(self) -> None:
        """The clock went back (a restarted simulation, a looped bag): stamps of the old timeline mean nothing
        now, and keeping them would drop every new command, stops included."""
        self._newest_s = -math.inf
        self._newest_was_stop = False

    def admit(self, stamp_s: float, moving: bool) -> bool:
        """True if the command stamped ``stamp_s`` [s] may be forwarded (and then becomes the newest)."""
        if stamp_s == 0.0:
            return True
        if stamp_s < self._newest_s or (stamp_s == self._newest_s and moving and self._newest_was_stop):
            return False
        self._newest_s = stamp_s
        self._newest_was_stop = not moving
        return True


class SensorWatchdog:
    """Tracks when each named sensor last delivered a message; stale when silent for ``timeout_s`` [s].

    A sensor that never delivered counts from ``start_s`` (the node's start), so a node gets one timeout's
    grace at start-up and then fails loudly if a sensor never comes.
    """

    def __init__(self, sensors: Iterable[str], timeout_s: float, start_s: float) -> None:
        if not math.isfinite(timeout_s) or timeout_s <= 0.0:
            raise ConfigError(f"sensor timeout must be a finite number > 0 [s], got {timeout_s!r}")
        self.timeout_s = timeout_s
        self._start_s = start_s
        self._last: Dict[str, Optional[float]] = {name: None for name in sensors}
        if not self._last:
            raise ConfigError("a sensor watchdog needs at least one sensor name")

    def restart(self, now_s: float) -> None:
        """Forget every sensor's last message and count from ``now_s`` again: ROS time moved backwards, and
        times from the old timeline would make a silent sensor look fresh (a negative age)."""
        self._start_s = now_s
        self._last = dict.fromkeys(self._last)

    def saw(self, sensor: str, now_s: float) -> None:
        if sensor not in self._last:
            raise ConfigError(f"sensor {sensor!r} is not watched (watched: {', '.join(self._last)})")
        self._last[sensor] = now_s

    def age(self, sensor: str, now_s: float) -> float:
        """[s] since the sensor's last message (since the start if it never sent one)."""
        last = self._last[sensor]
        return now_s - (last if last is not None else self._start_s)

    def problem(self, now_s: float) -> Optional[str]:
        """Why the sensors are not fresh (the stalest one), or None when every one is."""
        worst = max(self._last, key=lambda name: self.age(name, now_s))
        age = self.age(worst, now_s)
        if age <= self.timeout_s:
            return None
        if self._last[worst] is None:
            return f"no {worst} message since start ({age:.2f} s, sensor_timeout {self.timeout_s:.2f} s)"
        return f"stale {worst}: no message for {age:.2f} s (sensor_timeout {self.timeout_s:.2f} s)"
