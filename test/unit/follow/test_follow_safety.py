"""Safety rules of the motion nodes: finite commands, stop after silence, stale sensors."""

import math

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.safety import CommandOrder, CommandTimeout, SensorWatchdog, twist_problem


def test_finite_twist_is_fine():
    assert twist_problem((0.2, 0.0, 0.0), (0.0, 0.0, -1.0)) is None


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize("slot", range(6))
def test_any_non_finite_component_is_named(bad, slot):
    values = [0.1] * 6
    values[slot] = bad
    problem = twist_problem(values[:3], values[3:])
    assert problem is not None
    assert "non-finite" in problem and str(bad) in problem


def test_timeout_fires_once_after_silence():
    timeout = CommandTimeout(0.5)
    assert not timeout.due(100.0)  # nothing was ever sent: nothing to stop
    timeout.command(10.0)
    assert not timeout.due(10.49)
    assert timeout.due(10.5)
    assert not timeout.due(11.0)  # only once
    timeout.command(12.0)
    assert timeout.due(13.0)  # re-armed by the next command


def test_timeout_not_due_after_a_stop_and_disabled_with_zero():
    timeout = CommandTimeout(0.5)
    timeout.command(1.0)
    timeout.stopped()
    assert not timeout.due(5.0)
    off = CommandTimeout(0.0)
    off.command(1.0)
    assert not off.due(1000.0)


@pytest.mark.parametrize("bad", [-0.1, math.nan, math.inf])
def test_timeout_rejects_bad_values(bad):
    with pytest.raises(ConfigError, match="command timeout"):
        CommandTimeout(bad)


def test_watchdog_grace_at_start_then_stale_never_seen():
    dog = SensorWatchdog(["odom", "scan"], 0.5, start_s=100.0)
    assert dog.problem(100.4) is None
    problem = dog.problem(100.6)
    assert problem is not None and "since start" in problem and "sensor_timeout 0.50" in problem


def test_watchdog_names_the_stalest_sensor():
    dog = SensorWatchdog(["odom", "scan"], 0.5, start_s=0.0)
    dog.saw("odom", 1.0)
    dog.saw("scan", 1.2)
    assert dog.problem(1.45) is None
    problem = dog.problem(1.6)
    assert problem is not None and problem.startswith("stale odom") and "0.60 s" in problem
    dog.saw("odom", 1.6)
    assert dog.problem(1.6) is None
    problem = dog.problem(1.75)
    assert problem is not None and problem.startswith("stale scan")
    assert dog.age("scan", 2.0) == pytest.approx(0.8)


def test_watchdog_rejects_unknown_sensor_and_bad_timeout():
    dog = SensorWatchdog(["odom"], 1.0, start_s=0.0)
    with pytest.raises(ConfigError, match="'imu' is not watched"):
        dog.saw("imu", 0.0)
    with pytest.raises(ConfigError, match="sensor timeout"):
        SensorWatchdog(["odom"], 0.0, start_s=0.0)
    with pytest.raises(ConfigError, match="at least one"):
        SensorWatchdog([], 1.0, start_s=0.0)


def test_command_order_drops_a_command_older_than_one_forwarded_and_a_stop_wins_ties():
    order = CommandOrder()
    assert order.admit(10.0, moving=True)  # controller drives
    assert order.admit(10.2, moving=False)  # a behavior state stops the robot
    assert not order.admit(10.1, moving=True)  # the controller's last command arrives late: dropped
    assert not order.admit(10.2, moving=True)  # same stamp as the stop: the stop wins
    assert order.admit(10.2, moving=False)
    assert order.admit(10.3, moving=True)  # newer commands go through
    assert not order.admit(10.25, moving=False)  # an old stop is stale too
    assert order.admit(0.0, moving=True)  # unstamped: always forwarded, changes nothing
    assert not order.admit(10.29, moving=True)


def test_timeout_fires_once_when_the_clock_goes_back_before_the_last_command():
    timeout = CommandTimeout(0.5)
    timeout.command(100.0)
    assert timeout.due(20.0)  # a restarted simulation: the command's age is unknown, stop
    assert not timeout.due(20.1)  # once


def test_command_order_after_a_reset_admits_the_new_timeline():
    order = CommandOrder()
    assert order.admit(100.0, moving=True)
    assert not order.admit(5.0, moving=False)  # the old timeline would drop even a stop
    order.reset()
    assert order.admit(5.0, moving=False) and order.admit(5.1, moving=True)
    assert not order.admit(5.0, moving=True)  # ordered again within the new timeline


def test_watchdog_restart_forgets_the_old_timeline() -> None:
    # after ROS time jumped back, a sensor last seen at t=100 s must not look fresh (a negative age) at t=2 s
    dog = SensorWatchdog(["odom"], 0.5, start_s=0.0)
    dog.saw("odom", 100.0)
    assert dog.problem(2.0) is None  # the age is negative: the bug restart() is for
    dog.restart(2.0)
    assert dog.problem(2.4) is None  # one timeout of grace from the restart
    assert "no odom message since start" in (dog.problem(2.6) or "")
    dog.saw("odom", 2.7)
    assert dog.problem(2.8) is None
