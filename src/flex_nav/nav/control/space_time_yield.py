"""Giving way to moving people by planning the robot's speed along its path in space and time.

The path is fixed (the planner's); only *when* the robot is *where* on it is chosen, the path-velocity
decomposition of Kant and Zucker (1986). Every control tick (:meth:`SpaceTimeYield.decide`) the stretch of path
from ``back_m`` [m] behind the robot to as far as it can drive in the horizon is cut into cells of
``speed_mps * plan_step_s / 3`` [m], so that in one step of ``plan_step_s`` [s] the robot stands, drives one,
two or three cells forward (a third, two thirds or all of ``speed_mps``) or, when ``back_m`` > 0, backs up one
or two cells. A plan may back up only before it first drives forward: going and coming back within one plan
wastes the way, and executed one step at a time it made the robot dither.

Each person is predicted over ``horizon_s`` [s]: along the lane they walk when ``lanes`` is on
(:class:`~flex_nav.perception.walker_lanes.WalkerLanes`, learnt from every scan's tracks: walkers turn back at
the lane's ends), otherwise at constant velocity. The people planned around are the moving tracks (as
:class:`~flex_nav.nav.control.yielding.YieldRule` chooses them) and, with lanes, those standing at a lane's end
about to walk back. A plan's *score* is its smallest step score, where a step

- that moves scores the predicted gap (centre distance less both radii) to the nearest person, at both ends of
  the step, less ``moving_gap_m``: the social distance plus a little for the prediction's error;
- that stands scores the gap less ``standing_gap_m``: a person may pass a standing robot closer than the
  social distance (their doing), but must not be predicted to walk into it;
- that backs up also needs the local costmap free there (a walker's own marks do not count);
- predicted to touch a person (gap < 0) scores ``CONTACT_PENALTY_M`` lower: a plan that keeps out of someone's
  way at less than the social distance beats standing in it. A shortfall predicted later scores ``LATER_MPS``
  per second better, but stays a shortfall (when nothing keeps clear, the robot puts the meeting off).

Of the plans whose score is >= 0 the one ending farthest along the path is taken (ties: the one starting
faster); when none keeps its score >= 0, the one with the best score (farthest among equals). Scores are capped
at ``score_cap_m`` so that more room than that buys nothing over progress. Only its first step is driven:
forward at its speed (the controller's command when that is as fast: FREE; slower: SLOW, the turn rate scaled
to keep the curvature), standing (WAIT: the controller's turn in place is kept) or backing up straight
(ESCAPE); the next tick plans again from what the tracker then says. :attr:`SpaceTimeYield.last_plan` keeps the
chosen plan's positions.

Why a plan rather than rules: with three people looping across the robot's way (the h6 variant of S6) the
rules of :mod:`~flex_nav.nav.control.yielding` stop the robot where the first conflict tells it to, and that can
be inside the way of someone about to come back; looking at every place and time to stand in the horizon at
once finds the waiting place and the gap (issue 28). Why lanes: with constant-velocity predictions the plan
never saw a walker coming back from a wall, and 2-4 deg of tracker heading error over seconds changed the
plan every tick (h6 0.03-0.06 m while moving). Solved by dynamic programming over (step, state, cell): ``3 + 2``
moves, ``horizon_s / plan_step_s`` steps, two states (driven forward yet or not), about a hundred cells.

Pure: numpy, no ROS, no clock (times [s] are passed in); poses and tracks in the path's frame.
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

import numpy as np

from flex_nav.nav.control.yielding import PredictedPeople, YieldDecision, YieldMode, YieldParams, YieldRule
from flex_nav.nav.costmap.costmap_grid import CostmapGeometry
from flex_nav.nav.planar import Pose2D
from flex_nav.perception.moving_obstacles import Track
from flex_nav.perception.walker_lanes import WalkerLanes

FORWARD_CELLS = 3  # a step drives up to this many cells: cells are speed_mps * plan_step_s / 3 long
BACK_CELLS = 2  # and backs up at most this many (two thirds of speed_mps)
UNREACHED = -1e9  # score of a cell no plan reaches
CONTACT_PENALTY_M = 1.0  # [m] a step predicted to touch someone scores this much worse: contact before distance
LATER_MPS = 0.05  # [m/s] a shortfall predicted this many seconds later scores that much times better
SHORT_M = 1e-6  # [m] a shortfall scores at least this much below 0, however late
TIE_M = 1e-6  # [m] per cell of the first step: of two plans scoring the same, the one starting faster wins
SAME_SPEED_MPS = 1e-3  # [m/s] a planned speed this close to the controller's is the controller's
NOT_YET, DROVE = 0, 1  # plan states: not driven forward yet (may back up), driven forward (may not)


class SpaceTimeYield(YieldRule):
    """The planner of the module docstring; the parameters are :class:`YieldParams` (``planner`` "space_time").
    ``lanes``: the walkers' lanes to predict with (default: new ones when ``params.lanes``, else None); whoever
    owns the tracker should :meth:`WalkerLanes.update` them with every scan's tracks (else :meth:`decide` does,
    with the tracks it is given)."""

    def __init__(self, params: YieldParams, lanes: Optional[WalkerLanes] = None) -> None:
        super().__init__(params)
        self.step_s = params.plan_step_s
        self.steps = max(1, round(params.horizon_s / params.plan_step_s))
        self.cell_m = params.speed_mps * params.plan_step_s / FORWARD_CELLS
        backs = BACK_CELLS if params.back_m > 0.0 else 0
        self.moves = np.arange(-backs, FORWARD_CELLS + 1)  # cells per step
        self.lanes = lanes if lanes is not None else (WalkerLanes() if params.lanes else None)
        self.learns_in_decide = True  # False once the tracker's owner updates the lanes
        self.last_plan = np.zeros((0, 2))  # (K+1, 2) [m] the last chosen plan's positions, one per step

    def decide(
        self,
        now_s: float,
        pose: Pose2D,
        command: Tuple[float, float],
        *,
        path: np.ndarray,
        lengths: np.ndarray,
        s_robot: float,
        tracks: Sequence[Track],
        costs: Optional[np.ndarray] = None,
        geometry: Optional[CostmapGeometry] = None,
        speed: Optional[float] = None,
    ) -> YieldDecision:
        """The command to send instead of the controller's ``command`` (v [m/s], w [rad/s]); the arguments are
        those of :meth:`YieldRule.decide` (``speed`` is not needed: a plan's steps start at any speed)."""
        v_cmd, w_cmd = command
        if self.lanes is not None and self.learns_in_decide:
            self.lanes.update(now_s, tracks)
        people = self.people(pose, tracks)
        if not people:
            return self._sent(self._free(now_s, v_cmd, w_cmd))
        first, score, who = self.plan(pose, path, lengths, s_robot, people, costs, geometry)
        return self.decision_for_plan(now_s, command, people, first, score, who)

    def decision_for_plan(self, now_s: float, command: Tuple[float, float], people: Sequence[Track],  # noqa: PLR0917
                          first: int, score: float, who: int) -> YieldDecision:
        """The decision (sent: remembered for the resume hold) driving the first step of a plan returned by
        :meth:`plan` around ``people``, instead of the controller's ``command`` (v [m/s], w [rad/s])."""
        v_cmd, w_cmd = command
        v = first * self.cell_m / self.step_s
        if score >= 0.0 and first == FORWARD_CELLS and v_cmd <= v + SAME_SPEED_MPS:
            return self._sent(self._free(now_s, v_cmd, w_cmd))
        self._last_conflict_s = now_s
        track = people[who]
        about = f"track {track.track_id} ({track.speed:.2f} m/s)"
        unsafe = "" if score >= 0.0 else f"; no plan keeps the distance (short by {-score:.2f} m)"
        if first > 0:
            v = min(v, v_cmd) if v_cmd > 0.0 else v
            w = w_cmd * (v / v_cmd) if v_cmd > 1e-9 else 0.0
            return self._sent(YieldDecision(v, w, YieldMode.SLOW,
                                            f"yielding: {v:.2f} m/s, timing the way past {about}{unsafe}",
                                            track.track_id))
        if first == 0:
            return self._sent(YieldDecision(0.0, w_cmd, YieldMode.WAIT,
                                            f"yielding: standing for {about}{unsafe}", track.track_id))
        return self._sent(YieldDecision(v, 0.0, YieldMode.ESCAPE,
                                        f"yielding: backing up at {-v:.2f} m/s out of the way of {about}{unsafe}",
                                        track.track_id))

    def cells_per_step(self, v: float) -> int:
        """The move (cells per step, one of :attr:`moves`) nearest to driving at ``v`` [m/s]."""
        return int(np.clip(round(v * self.step_s / self.cell_m), self.moves[0], self.moves[-1]))

    def people(self, pose: Pose2D, tracks: Sequence[Track]) -> List[Track]:
        """The tracks planned around: the moving ones in range and, with lanes, those turning at a lane's end."""
        people = self.moving(pose, tracks)
        if self.lanes is not None:
            p = self.params
            people += [t for t in tracks if t.speed < p.min_track_speed_mps
                       and math.hypot(t.x - pose[0], t.y - pose[1]) <= p.max_range_m
                       and self.lanes.turning_at(t) is not None]
        return people

    def predicted(self, people: Sequence[Track], times: np.ndarray) -> np.ndarray:
        """(M, K, 2) [m] where ``people`` are predicted at ``times`` (K,) [s] from now."""
        if self.lanes is not None:
            return np.stack([self.lanes.predict(t, times) for t in people])
        centres = np.array([[t.x, t.y] for t in people])
        velocity = np.array([[t.vx, t.vy] for t in people])
        return np.asarray(centres[:, None, :] + velocity[:, None, :] * times[None, :, None])

    def plan(self, pose: Pose2D, path: np.ndarray, lengths: np.ndarray, s_robot: float,  # noqa: PLR0917
             people: Sequence[Track], costs: Optional[np.ndarray] = None,
             geometry: Optional[CostmapGeometry] = None, *, only_first: Optional[int] = None,
             standing_gap_m: Optional[float] = None, moving_gap_m: Optional[float] = None) -> Tuple[int, float, int]:
        """(first step in cells per step, the plan's score [m], index in ``people`` of the nearest person on
        the plan) of the best plan of the module docstring from the robot at arc length ``s_robot`` [m]; the
        plan's positions go to :attr:`last_plan`. ``only_first``: the best of the plans whose first step is
        that many cells (one of :attr:`moves`); ``standing_gap_m``, ``moving_gap_m`` [m]: kept while standing,
        while moving, instead of the parameters'."""
        p = self.params
        start = max(float(lengths[0]), s_robot - p.back_m)
        end = min(float(lengths[-1]), s_robot + p.speed_mps * p.horizon_s)
        behind = math.floor((s_robot - start) / self.cell_m + 1e-9)
        count = behind + math.floor((end - s_robot) / self.cell_m + 1e-9) + 1
        arc = s_robot + (np.arange(count) - behind) * self.cell_m
        cells = np.stack((np.interp(arc, lengths, path[:, 0]), np.interp(arc, lengths, path[:, 1])), axis=1)
        times = np.arange(self.steps + 1) * self.step_s
        future = self.predicted(people, times)  # (M, K+1, 2)
        radii = np.array([t.radius for t in people]) + p.robot_radius_m
        dist = np.hypot(future[:, :, None, 0] - cells[None, None, :, 0],
                        future[:, :, None, 1] - cells[None, None, :, 1]) - radii[:, None, None]  # (M, K+1, N)
        gap = dist.min(axis=0)  # (K+1, N)
        nearest = dist.argmin(axis=0)
        blocked = self._blocked_behind(cells, behind, people, costs, geometry)
        score, first, states, history = self._search(gap, times, behind, blocked, only_first,
                                                     p.standing_gap_m if standing_gap_m is None else standing_gap_m,
                                                     p.moving_gap_m if moving_gap_m is None else moving_gap_m)
        feasible = np.flatnonzero(score >= 0.0)
        goal = int(feasible.max()) if feasible.size else int(np.flatnonzero(score >= float(score.max()) - 1e-9).max())
        self.last_plan = cells[self._walk_back(history, goal, int(states[goal]))]
        after_first = min(max(behind + int(first[goal]), 0), count - 1)
        return int(first[goal]), float(score[goal]), int(nearest[1, after_first])

    def _search(self, gap: np.ndarray, times: np.ndarray, behind: int, blocked: np.ndarray,  # noqa: PLR0917
                only_first: Optional[int], standing_gap_m: float, moving_gap_m: float
                ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, List[np.ndarray]]:
        """The dynamic programme over (step, state, cell) on the predicted ``gap`` (K+1, N) [m], keeping
        ``standing_gap_m`` [m] while standing and ``moving_gap_m`` [m] while moving, with the first move
        ``only_first`` cells (None: any): per cell the
        best score [m], the first move (cells) of its plan, its final state and, per step, where each (state,
        cell) came from ((2, 2, N): state and move index)."""
        p = self.params
        count = gap.shape[1]
        columns = np.arange(count)
        source = columns[None, :] - self.moves[:, None]  # (moves, N): where a move into a cell came from
        allowed = (source >= 0) & (source < count) & ~((self.moves < 0)[:, None] & blocked[None, :])
        source = np.clip(source, 0, count - 1)
        standing = self.moves == 0
        forward = self.moves > 0
        # (state from, state to) -> the moves that make that transition: backing only before driving forward
        transitions = ((NOT_YET, NOT_YET, ~forward), (NOT_YET, DROVE, forward), (DROVE, DROVE, self.moves >= 0))
        score = np.full((2, count), UNREACHED)
        score[NOT_YET, behind] = p.score_cap_m
        first = np.zeros((2, count), dtype=np.int64)  # the first move of the best plan into each state and cell
        history: List[np.ndarray] = []
        for k in range(self.steps):
            kept = np.where(standing[:, None], gap[k + 1][None, :], np.minimum(gap[k][source], gap[k + 1][None, :]))
            need = np.where(standing, standing_gap_m, moving_gap_m)[:, None]
            step = kept - need - CONTACT_PENALTY_M * (kept < 0.0)
            step = np.where(step < 0.0, np.minimum(step + LATER_MPS * times[k + 1], -SHORT_M), step)
            step = np.minimum(step, p.score_cap_m)
            new_score = np.full((2, count), UNREACHED)
            new_first = np.zeros((2, count), dtype=np.int64)
            came = np.zeros((2, 2, count), dtype=np.int64)
            for state_from, state_to, moves in transitions:
                usable = moves & (self.moves == only_first) if k == 0 and only_first is not None else moves
                candidate = np.where(allowed & usable[:, None], np.minimum(score[state_from][source], step), UNREACHED)
                firsts = np.broadcast_to(self.moves[:, None], source.shape) if k == 0 else first[state_from][source]
                best = (candidate + TIE_M * firsts).argmax(axis=0)  # ties: the plan that starts forward
                value = candidate[best, columns]
                better = value > new_score[state_to]
                new_score[state_to] = np.where(better, value, new_score[state_to])
                new_first[state_to] = np.where(better, firsts[best, columns], new_first[state_to])
                came[state_to, 0] = np.where(better, state_from, came[state_to, 0])
                came[state_to, 1] = np.where(better, best, came[state_to, 1])
            score, first = new_score, new_first
            history.append(came)
        states = score.argmax(axis=0)
        return score[states, columns], first[states, columns], states, history

    def _walk_back(self, history: Sequence[np.ndarray], goal: int, state: int) -> List[int]:
        """The cells (K+1) of the plan ending in ``goal`` in ``state``, first to last."""
        cell, visited = goal, [goal]
        for came in reversed(history):
            state, move = int(came[state, 0, cell]), int(came[state, 1, cell])
            cell -= int(self.moves[move])
            visited.append(cell)
        return visited[::-1]

    def _blocked_behind(self, cells: np.ndarray, behind: int, people: Sequence[Track],
                        costs: Optional[np.ndarray], geometry: Optional[CostmapGeometry]) -> np.ndarray:
        """(N,) True for the cells behind the robot that the local costmap has an obstacle on (beyond the
        walkers' own marks): backing up into them is no way out."""
        blocked = np.zeros(len(cells), dtype=bool)
        if costs is None or geometry is None or behind == 0:
            return blocked
        predicted = PredictedPeople(people, self.times[:1], self.params)
        for i in range(behind):
            if not self._free_of_obstacles(cells[i:i + 1], predicted, costs, geometry):
                blocked[:i + 1] = True  # nothing behind an obstacle is reachable backing straight
        return blocked
