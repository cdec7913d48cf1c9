"""What one scenario run measured (:class:`RunResult`) and the robot's clearance to people.

People in the simulator are kinematic and scripted, so where each one was at a simulated time follows
from the world file alone: standing at the first waypoint until it starts walking (its ``start`` time or
its first ``start_walking`` event), then :meth:`Person.pose_after` of the time walked. ``stop_walking``
events are taken into account as well. The clearance is the centre distance minus the person's radius
and the robot's radius (negative = overlap).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import asdict, dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

from flex_nav.nav.control.social_distance import ContactCause, contact_cause

ROBOT_RADIUS_M = 0.171  # [m] TurtleBot 4 (sim/robots/turtlebot4.yaml)


@dataclass
class RunResult:
    """One run of one scenario with one behavior and one seed."""

    world: str
    behavior: str
    seed: int
    success: bool = False
    time_s: float = math.nan  # [s] simulated time from the goal to arrival (NaN if not reached)
    path_m: float = 0.0  # [m] distance driven (ground truth)
    heading_error_deg: float = math.nan  # [deg] final heading minus the goal's (ground truth; NaN: not reached)
    pushes_tried: int = 0
    pushes_succeeded: int = 0
    people_contacts: int = 0  # contacts that began between the robot and a person (all of them)
    # the same split by whose doing they were (:func:`classify_contact`): the robot drove into the person, or the
    # person walked into a standing robot or one whose touching point moved away or along; results recorded
    # before the split have 0 and 0 here whatever people_contacts says
    people_contacts_robot_caused: int = 0
    people_contacts_person_caused: int = 0
    min_people_clearance_m: float = math.inf  # [m] smallest robot-person gap (inf: no person in the world)
    # [m] the same while the robot moved (faster than MOVING_MPS): a person walking up to a standing robot is not
    # the robot coming close (inf: no person, or never near one while moving)
    min_people_clearance_moving_m: float = math.inf
    # [s] simulated time from start to goal of every trip (``scenario_run --trips N``: the robot drives back to
    # the start between trips, untimed, and keeps what it learnt, e.g. the obstacle memory); the first is time_s;
    # NaN: that trip's goal not reached; empty: one trip
    trip_times_s: List[float] = field(default_factory=list)
    note: str = ""  # why it ended when not reached
    picture: str = ""

    def to_dict(self) -> Dict[str, Any]:
        values = asdict(self)
        for key in ("time_s", "heading_error_deg", "min_people_clearance_m",
                    "min_people_clearance_moving_m"):  # JSON has no NaN / inf
            value = values[key]
            values[key] = None if not math.isfinite(value) else value
        values["trip_times_s"] = [t if math.isfinite(t) else None for t in self.trip_times_s]
        return values

    @classmethod
    def from_dict(cls, values: Dict[str, Any]) -> RunResult:
        data = dict(values)
        for key in ("time_s", "heading_error_deg"):  # results recorded before the heading was measured lack it
            data[key] = math.nan if data.get(key) is None else float(data[key])
        for key in ("min_people_clearance_m", "min_people_clearance_moving_m"):  # older results lack the second
            clearance = data.get(key)
            data[key] = math.inf if clearance is None else float(clearance)
        data["trip_times_s"] = [math.nan if t is None else float(t) for t in data.get("trip_times_s") or []]
        return cls(**data)


def walking_intervals(person: Any, events: Sequence[Any]) -> List[Tuple[float, float]]:
    """[(start, end)] simulated times [s] while ``person`` walks (end inf: until the end)."""
    if not person.walks:
        return []
    changes: List[Tuple[float, bool]] = []
    if person.start_time is not None:
        changes.append((float(person.start_time), True))
    for event in events:
        if event.target == person.name and event.action in ("start_walking", "stop_walking"):
            changes.append((float(event.time), event.action == "start_walking"))
    changes.sort(key=lambda c: c[0])
    intervals: List[Tuple[float, float]] = []
    start = None
    for when, walking in changes:
        if walking and start is None:
            start = when
        elif not walking and start is not None:
            intervals.append((start, when))
            start = None
    if start is not None:
        intervals.append((start, math.inf))
    return intervals


def person_position(person: Any, intervals: Sequence[Tuple[float, float]], world_s: float) -> Tuple[float, float]:
    """(x, y) [m] of ``person`` at ``world_s`` [s] of the world's time (simulated time since the world's start)."""
    walked = sum(max(0.0, min(world_s, end) - start) for start, end in intervals)
    x, y, _yaw = person.pose_after(walked)
    return x, y


MOVING_MPS = 0.02  # [m/s] the robot counts as moving above this speed (ground truth)


def classify_contact(pose: Tuple[float, float, float], v: float, w: float,
                     point: Tuple[float, float]) -> ContactCause:
    """Whose doing a contact with a person was: the robot at ``pose`` (x, y, yaw) [m, m, rad] driving at (``v``
    [m/s], ``w`` [rad/s]) when it touched them at ``point`` (x, y) [m], both in the world frame
    (:func:`flex_nav.nav.control.social_distance.contact_cause`, the point carried into the robot's base frame;
    its direction from the base's centre is the footprint's outward normal of a round base)."""
    x, y, yaw = pose
    dx, dy = point[0] - x, point[1] - y
    c, s = math.cos(yaw), math.sin(yaw)
    local = (c * dx + s * dy, -s * dx + c * dy)
    if math.hypot(*local) < 1e-9:
        raise ValueError(f"contact point {point!r} at the robot's centre {pose!r}: no direction to classify it by")
    return contact_cause(v, w, local, stopped_speed_mps=MOVING_MPS)


COMMAND_HOLD_S = 0.7  # [s] a robot moves of its own accord this long after its last moving command: twice its
# braking from top speed (0.306 m/s at the simulated TurtleBot 4's 0.9 m/s^2: 0.34 s)


def commanded_at(commands: Sequence[Tuple[float, float]], sim_s: float,
                 times: Optional[Sequence[float]] = None) -> bool:
    """True when one of ``commands`` ((sim s, v [m/s]) in time order) faster than :data:`MOVING_MPS` was given
    within :data:`COMMAND_HOLD_S` before ``sim_s``; ``times``: the commands' times, when the caller asks often."""
    index = bisect.bisect_right(times if times is not None else [t for t, _v in commands], sim_s)
    for t, v in reversed(commands[:index]):
        if sim_s - t > COMMAND_HOLD_S:
            return False
        if abs(v) > MOVING_MPS:
            return True
    return False


def people_clearance(world: Any, trajectory: Sequence[Tuple[float, float, float]], goal_sim_s: float = 0.0,
                     robot_radius_m: float = ROBOT_RADIUS_M, moving_only: bool = False, *,
                     commands: Optional[Sequence[Tuple[float, float]]] = None, world_start_s: float = 0.0) -> float:
    """Smallest gap [m] between the robot (trajectory of (sim s, x, y) from ``goal_sim_s`` on) and any person
    of ``world``; inf without people or samples. ``moving_only``: only at samples where the robot moved faster
    than :data:`MOVING_MPS` since the previous sample and, given its ``commands`` ((sim s, v [m/s]), the
    velocity commands it received), where it was also told to move (:func:`commanded_at`): a standing robot
    shoved by a walker moves, but not of its own accord (S6: a walker pushed a stopped robot at 0.8 m/s).
    ``world_start_s`` [s]: the simulated time the world's script started at (people walk from there on)."""
    moving = [True] * len(trajectory)
    times = [t for t, _v in commands] if commands is not None else None
    if moving_only:
        moving = [False] + [
            t1 > t0 and math.hypot(x1 - x0, y1 - y0) / (t1 - t0) > MOVING_MPS
            and (commands is None or commanded_at(commands, t1, times))
            for (t0, x0, y0), (t1, x1, y1) in zip(trajectory, trajectory[1:])]
    best = math.inf
    for person in world.people:
        intervals = walking_intervals(person, world.events)
        for (t, x, y), counted in zip(trajectory, moving):
            if t < goal_sim_s or not counted:
                continue
            px, py = person_position(person, intervals, t - world_start_s)
            best = min(best, math.hypot(x - px, y - py) - person.radius - robot_radius_m)
    return best
