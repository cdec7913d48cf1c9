"""System test of a deployment split over two computers, and of what stops the robot when the link drops.

Two network namespaces joined by a veth pair stand in for the robot's computer and the operator's
(:class:`flex_nav.testing.netns.NetnsPair`, private 10.231.X.1/.2 addresses). Each side's processes run with that side's
address in ``ROS_IP`` and ``ROS_MASTER_URI`` pointing at the one master, started the way a user would:

robot's computer     roslaunch flex_nav sim.launch world:=two_rooms heartbeat_timeout:=0.5   (base, map, twist_relay)
                     roslaunch flex_nav flex_nav_robot.launch part:=robot                    (servers, controllers)
operator's computer  roslaunch flex_nav flex_nav_robot.launch part:=operator                 (behavior runner)
                     test/system/two_hosts_goal.py (goals), rosrun flex_nav operator status
the master           roscore on the operator's computer, or on the robot's (parametrized)

Scenario: a goal is reached across the link; the next goal starts and, with the robot driving, the robot's end
of the link goes down: twist_relay and the controllers lose the runner's heartbeat and the robot stops, measured
on the simulator's ground truth recorded on the robot's side (real-time factor 1). The link comes back: the
runner is done with the interrupted goal, the operator tool gets answers, and a new goal is reached. A third
variant leaves the heartbeat to twist_relay alone (the controllers drive on): the fail-safe must hold the base.

Bounds: twist_relay's zero Twist reaches the base within heartbeat_timeout + 0.2 s of the link going down
(wall time); the ground truth stands (< 0.01 m/s) within that plus the braking the base needs from its peak
speed at its acceleration limit (0.5 s from 0.5 m/s at 1 m/s^2: no base stops from cruising speed in 0.2 s);
it does not move again and the simulated base does not stall while the link is down.
Skipped (with the reason) where network namespaces cannot be made: not root, no ``ip``, ``ip netns`` refused.
"""

from __future__ import annotations

import contextlib
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Dict, List, Optional, Tuple

import pytest
from harness import REPO_ROOT, run_command_bounded

from flex_nav.testing.netns import Host, NetnsPair, netns_unavailable_reason
from flex_nav.testing.private_master import ros_environment
from flex_nav.testing.process import ManagedProcess
from flex_nav_sim.profiles import load_profile

ROBOT = "robot1"
PROFILE = "kobuki"
WORLD = "two_rooms"  # no walking people: the same run every time
MASTER_PORT = 11311  # inside the test's own namespaces no other master can hold it
RELAY_TIMEOUT_S = 0.5  # [s] twist_relay's ~timeout (config/turtlebot2.yaml, sim.launch relay_timeout)
HEARTBEAT_TIMEOUT_S = 0.5  # [s, wall] the split launch's heartbeat_timeout: twist_relay's timeout
STOP_MARGIN_S = 0.2  # [s] the allowance on top of the timeout
STANDSTILL_MPS = 0.01  # [m/s] ground-truth speed below which the robot stands
DRIVING_MPS = 0.45  # [m/s] the link goes down once the robot drives at least this fast (pure pursuit: 0.5)
LINK_DOWN_S = 3.0  # [s, wall] the outage: several times the stop time, so standing still is seen too
MAX_TRUTH_GAP_S = 0.5  # [s, wall] the simulated base runs on through the outage (its ground truth comes at 48 Hz)
STARTUP_TIMEOUT_S = 60.0  # [s, wall] master, simulator
GOAL_TIMEOUT_S = 120.0  # [s, wall] one goal, the runner's start included for the first
COMMAND_TIMEOUT_S = 30.0  # [s, wall] bound of one short command (probe, operator status)
GOALS = {  # (x [m], y [m], yaw [deg]) in the west room of two_rooms; the robot starts at (1.5, 2.0, 0)
    "first": (3.8, 2.0, 0.0),
    "interrupted": (1.0, 2.0, 180.0),
    "after": (3.0, 1.7, 0.0),
}


@dataclass
class Side:
    """One computer: its namespace, address and ROS environment."""

    host: Host
    env: Dict[str, str]
    logs: Path

    def start(self, name: str, argv: List[str]) -> ManagedProcess:
        return ManagedProcess(self.host.command(argv), env=self.env, log_path=self.logs / f"{name}.log")

    def run(self, argv: List[str], timeout_s: float) -> Tuple[int, str]:
        outcome = run_command_bounded(self.host.command(argv), env=self.env, timeout_s=timeout_s)
        return outcome.returncode, outcome.output


def side(host: Host, master_uri: str, out: Path, name: str) -> Side:
    env = ros_environment(master_uri, out / f"ros_home_{name}")
    env.pop("ROS_HOSTNAME")  # it would win over ROS_IP
    env["ROS_IP"] = host.address
    logs = out / f"logs_{name}"
    logs.mkdir(parents=True)
    return Side(host, env, logs)


def wait_for_master(sides: List[Side], uri: str) -> None:
    """Until the master at ``uri`` answers from every side (over the link for one of them)."""
    probe = ("import sys; from flex_nav.ros.master_probe import master_is_up; "
             "sys.exit(0 if master_is_up(sys.argv[1]) else 1)")
    deadline = time.monotonic() + STARTUP_TIMEOUT_S
    for one in sides:
        while one.run([sys.executable, "-c", probe, uri], COMMAND_TIMEOUT_S)[0] != 0:
            assert time.monotonic() < deadline, f"no master at {uri} from {one.host.namespace}"
            time.sleep(0.2)


def diagnosis(out: Path) -> str:
    """The last lines the runner, pure_pursuit_topic and twist_relay logged (rospy's own lines left out)."""
    parts = []
    for home, node in (("operator", "behavior_runner"), ("robot", "pure_pursuit_topic"), ("robot", "twist_relay")):
        for log in sorted((out / f"ros_home_{home}" / "log").glob(f"*/{ROBOT}-{node}-*[0-9].log")):
            lines = [line for line in log.read_text(errors="replace").splitlines() if "[rospy." not in line]
            parts.append(f"\n--- {log.name}:\n" + "\n".join(lines[-25:]))
    return "".join(parts)


@dataclass
class Record:
    """The robot-side observer's lines (two_hosts_observer.py) read so far: ground truth and base commands."""

    path: Path
    truth: List[Tuple[float, float, float]] = field(default_factory=list)  # (wall [s], sim [s], speed [m/s])
    commands: List[Tuple[float, float, float]] = field(default_factory=list)  # (wall [s], v [m/s], w [rad/s])
    _offset: int = 0  # bytes of the file read

    def read(self) -> Record:
        """Take in the complete lines written since the last call."""
        if not self.path.exists():
            return self
        with self.path.open("rb") as source:
            source.seek(self._offset)
            chunk = source.read()
        complete = chunk[: chunk.rfind(b"\n") + 1]  # a last line being written waits for the next call
        self._offset += len(complete)
        for line in complete.decode().splitlines():
            fields = line.split(",")
            if fields[0] == "gt":
                self.truth.append((float(fields[1]), float(fields[2]), float(fields[5])))
            elif fields[0] == "cmd":
                self.commands.append((float(fields[1]), float(fields[3]), float(fields[4])))
        return self

    def wait_for(self, predicate: Callable[[Record], bool], what: str, timeout_s: float,
                 processes: List[ManagedProcess]) -> None:
        """Until ``predicate(self)`` holds; fails when ``timeout_s`` [s] pass or one of ``processes`` exits."""
        deadline = time.monotonic() + timeout_s
        while not predicate(self.read()):
            dead = [p for p in processes if not p.running()]
            assert not dead, f"{dead[0].argv} exited:\n{dead[0].log_tail(3000)}"
            assert time.monotonic() < deadline, f"observer: no {what} within {timeout_s:.0f} s"
            time.sleep(0.02)


@dataclass
class Stop:
    """What the base did while the link was down (times from the moment it went down)."""

    speed_at_down: float  # [m/s] ground truth when the link went down
    peak_speed: float  # [m/s] fastest ground truth between the link going down and the stop (or the link's return)
    truth_gap_s: float  # [s, wall] longest silence of the ground truth
    zero_command_s: Optional[float]  # [s, wall] to the first zero Twist to the base (None: none came)
    command_after_zero: Optional[Tuple[float, float, float]]  # a motion command after the zero one, if any
    stop_s: Optional[float]  # [s, sim] to a ground-truth speed below STANDSTILL_MPS (None: never)
    moved_after_stop: Optional[Tuple[float, float]]  # (sim [s], speed [m/s]) of a sample moving again, if any


def _s(seconds: Optional[float]) -> str:
    return "never" if seconds is None else f"{seconds:.3f} s"


def measure_stop(record: Record, down_wall: float, up_wall: float) -> Stop:
    """The stop after the link went down at ``down_wall`` [s, wall], until it came back at ``up_wall``."""
    before = [s for s in record.truth if s[0] <= down_wall]
    during = [s for s in record.truth if down_wall < s[0] <= up_wall]
    assert before and during, "no ground truth around the outage"
    down_sim = during[0][1] - (during[0][0] - down_wall)  # the first sample after, less its wall delay
    walls = [before[-1][0], *(s[0] for s in during), up_wall]
    standing = next((i for i, s in enumerate(during) if abs(s[2]) < STANDSTILL_MPS), len(during))
    commands = [c for c in record.commands if down_wall < c[0] <= up_wall]
    zero = next((i for i, c in enumerate(commands) if c[1] == 0.0 and c[2] == 0.0), len(commands))
    return Stop(
        speed_at_down=before[-1][2],
        peak_speed=max(abs(s[2]) for s in [before[-1], *during[:standing]]),
        truth_gap_s=max(b - a for a, b in zip(walls, walls[1:])),
        zero_command_s=commands[zero][0] - down_wall if zero < len(commands) else None,
        command_after_zero=next((c for c in commands[zero:] if c[1] != 0.0 or c[2] != 0.0), None),
        stop_s=during[standing][1] - down_sim if standing < len(during) else None,
        moved_after_stop=next(((s[1], s[2]) for s in during[standing:] if abs(s[2]) >= STANDSTILL_MPS), None),
    )


@pytest.mark.ros
@pytest.mark.parametrize(("master_on", "controllers_watch"), [("operator", True), ("robot", True), ("operator", False)],
                         ids=["master_on_operator", "master_on_robot", "twist_relay_alone"])
def test_robot_stops_when_the_link_to_the_operator_drops(tmp_path: Path, request: pytest.FixtureRequest,
                                                         master_on: str, controllers_watch: bool) -> None:
    # twist_relay_alone: the controllers do not watch the heartbeat and drive on; twist_relay must hold the base
    reason = netns_unavailable_reason()
    if reason is not None:
        pytest.skip(reason)
    started = time.monotonic()
    with contextlib.ExitStack() as stack:
        pair = stack.enter_context(NetnsPair())  # stopped last: ends whatever is left inside, deletes both
        robot_host, operator_host = pair.first, pair.second
        # The simulator writes its high-rate topics (odom, ground truth, /clock, tf) synchronously (sim_bridge): a
        # subscriber across a dead link stalls it, and with it the robot's clock, once that socket's send buffer is
        # full, about 1 s into the outage with the default 16 kB. A base driver queues instead; with 4 MB the
        # simulated base runs on through the outage as a base would, and the heartbeat alone stops the robot.
        pair.sysctl(robot_host, "net.ipv4.tcp_wmem", "4096 4194304 4194304")
        master_host = operator_host if master_on == "operator" else robot_host
        uri = f"http://{master_host.address}:{MASTER_PORT}/"
        robot = side(robot_host, uri, tmp_path, "robot")
        operator = side(operator_host, uri, tmp_path, "operator")
        master_side = operator if master_on == "operator" else robot

        def start(one: Side, name: str, argv: List[str]) -> ManagedProcess:
            proc = one.start(name, argv)
            stack.callback(proc.stop)
            return proc

        processes = [start(master_side, "roscore", ["roscore", "-p", str(MASTER_PORT)])]
        wait_for_master([master_side, robot if master_side is operator else operator], uri)

        record = Record(tmp_path / "observer.csv")
        processes += [
            start(robot, "sim", ["roslaunch", "flex_nav", "sim.launch", f"world:={WORLD}", f"robot:={ROBOT}",
                                 "rtf:=1", "camera:=false", f"relay_timeout:={RELAY_TIMEOUT_S}",
                                 f"heartbeat_timeout:={HEARTBEAT_TIMEOUT_S}"]),
            start(robot, "navigation", ["roslaunch", "flex_nav", "flex_nav_robot.launch", "part:=robot",
                                        f"robot:={ROBOT}", f"profile:={PROFILE}",
                                        f"heartbeat_timeout:={HEARTBEAT_TIMEOUT_S if controllers_watch else 0}"]),
            start(robot, "observer", [sys.executable, str(REPO_ROOT / "test" / "system" / "two_hosts_observer.py"),
                                      ROBOT, str(record.path)]),
        ]
        record.wait_for(lambda r: bool(r.truth), "ground truth", STARTUP_TIMEOUT_S, processes)  # use_sim_time is set
        processes.append(start(operator, "runner", [
            "roslaunch", "flex_nav", "flex_nav_robot.launch", "part:=operator", f"robot:={ROBOT}",
            f"profile:={PROFILE}", "behavior:=flex_planner", "autonomy:=full"]))
        goal_script = [sys.executable, str(REPO_ROOT / "test" / "system" / "two_hosts_goal.py"), ROBOT]

        def goal_argv(name: str) -> List[str]:
            return [*goal_script, *(str(v) for v in GOALS[name]), str(GOAL_TIMEOUT_S)]

        # 1. A goal reached across the link.
        code, output = operator.run(goal_argv("first"), GOAL_TIMEOUT_S + COMMAND_TIMEOUT_S)
        assert code == 0 and "ARRIVED" in output, f"first goal ({code}):\n{output[-3000:]}{diagnosis(tmp_path)}"

        # 2. The next goal; the link goes down with the robot driving, and comes back LINK_DOWN_S later.
        interrupted = start(operator, "goal_interrupted", goal_argv("interrupted"))
        record.wait_for(lambda r: bool(r.truth) and r.truth[-1][2] > DRIVING_MPS, f"driving at {DRIVING_MPS} m/s",
                        GOAL_TIMEOUT_S, [*processes, interrupted])
        down_wall = time.monotonic()
        pair.set_link(robot_host, up=False)
        time.sleep(LINK_DOWN_S)
        up_wall = time.monotonic()
        pair.set_link(robot_host, up=True)

        # 3. The operator's side sees the robot again: the runner is done with the interrupted goal (reached
        # after a replan, or given up), the operator tool gets answers, a new goal is reached.
        with contextlib.suppress(Exception):
            interrupted.popen.wait(GOAL_TIMEOUT_S)
        outcome = interrupted.log_tail(3000)
        stop = measure_stop(record.read(), down_wall, up_wall)
        a_max = load_profile(PROFILE).drive.max_linear_acceleration
        braking_s = stop.peak_speed / a_max  # the base ramps a zero command down at its acceleration limit
        print(f"\n{request.node.callspec.id}: link down at {stop.speed_at_down:.2f} m/s; zero Twist to the base after "
              f"{_s(stop.zero_command_s)} (wall); ground truth below {STANDSTILL_MPS} m/s after {_s(stop.stop_s)} "
              f"(sim; braking from the peak {stop.peak_speed:.2f} m/s takes {braking_s:.2f} s at {a_max} m/s^2); "
              f"longest ground-truth gap {stop.truth_gap_s:.3f} s", flush=True)
        assert interrupted.popen.returncode in (0, 1), \
            f"interrupted goal not ended by the runner:\n{outcome}{diagnosis(tmp_path)}"
        code, output = operator.run([sys.executable, "-m", "flex_nav.apps.operator_cli", "--runner",
                                     f"/{ROBOT}/behavior_runner", "status"], COMMAND_TIMEOUT_S)
        assert code == 0, f"operator status ({code}):\n{output[-3000:]}{diagnosis(tmp_path)}"
        code, output = operator.run(goal_argv("after"), GOAL_TIMEOUT_S + COMMAND_TIMEOUT_S)
        assert code == 0 and "ARRIVED" in output, \
            f"goal after the outage ({code}):\n{output[-3000:]}{diagnosis(tmp_path)}"
    last = (outcome.strip().splitlines() or ["no output"])[-1]
    print(f"interrupted goal: {last}; test wall time {time.monotonic() - started:.0f} s")
    assert stop.speed_at_down > DRIVING_MPS, "the robot was not driving when the link went down"
    assert stop.truth_gap_s < MAX_TRUTH_GAP_S, "the robot's side stalled while the link was down"
    assert stop.zero_command_s is not None, "no zero Twist reached the base while the link was down"
    assert stop.zero_command_s <= HEARTBEAT_TIMEOUT_S + STOP_MARGIN_S
    assert stop.command_after_zero is None, "motion commanded while the link was down"
    assert stop.stop_s is not None, "the robot never stood while the link was down"
    assert stop.stop_s <= HEARTBEAT_TIMEOUT_S + STOP_MARGIN_S + braking_s
    assert stop.moved_after_stop is None, "the robot moved again while the link was down"
