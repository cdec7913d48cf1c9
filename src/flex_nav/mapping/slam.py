"""2D lidar graph SLAM: keyframes linked by scan matching, loops closed by matching against older submaps, the
pose graph optimised by gtsam, the occupancy grid rebuilt from the optimised poses.

Per scan (:meth:`GraphSlam.add_scan`): nothing happens until the odometry says the robot moved
``minimum_travel_distance`` [m] or turned ``minimum_travel_heading`` [rad] since the last keyframe. Then:

1. **link**: the odometry since the last keyframe predicts the pose; the scan is matched (``scan_matcher``)
   against the local submap (the hits of the last ``scan_buffer_size`` keyframes within
   ``scan_buffer_maximum_scan_distance`` [m]) within ``correlation_search_space_dimension`` [m] (full width) and
   ± ``coarse_search_angle_offset`` [rad] of the prediction. A response of at least
   ``link_match_minimum_response_fine`` gives a SCAN_MATCH edge from the last keyframe with the match's covariance;
   a poorer one (a featureless view) an ODOMETRY edge with the odometry's.
2. **loop**: among the keyframes at least ``loop_minimum_travel`` [m] of driving back and within
   ``loop_search_maximum_distance`` [m] of the new pose, the nearest is taken with its neighbours
   (``loop_match_minimum_chain_size`` keyframes) as a submap, and the scan matched against it over
   ``loop_search_space_dimension`` [m] (full width). The closure is accepted only if the response reaches
   ``loop_match_minimum_response_fine`` **and** the best pose outside ``loop_match_uniqueness_radius`` [m] of it
   scores below ``loop_match_uniqueness_ratio`` of it (a corridor of identical doors gives two peaks: no closure)
   **and** matching the other way (the old keyframe's scan against the new pose's submap) lands within
   ``loop_match_agreement_distance`` [m] of the same relative pose. An accepted closure adds a LOOP edge (the
   graph's robust kernel bounds what a false one could still do) and the graph is optimised.

The map frame puts the first keyframe at ``map_start_pose`` (slam_toolbox's parameter; default: at its odometry
pose, so that ``map → odom`` starts as the identity); ``map → odom`` is the last keyframe's optimised pose composed
with the inverse of its odometry (:meth:`GraphSlam.map_to_odom`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, NamedTuple, Optional, Tuple

import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.localization.scan import ScanBeams
from flex_nav.mapping.occupancy import OccupancyParams, ScanRays, rasterize, scan_rays
from flex_nav.mapping.pose_graph import EdgeKind, PoseGraph
from flex_nav.mapping.scan_matcher import Lookup, Match, MatcherParams, ScanMatcher, Window
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose, transform_poses

LOOKUP_SIGMAS = 4.0  # [-] exp(-8) = 3e-4: beyond this many sigma a lookup cell scores nothing


@dataclass(frozen=True)
class SlamParams:
    """The mapper's settings (slam_toolbox's names where the meaning is the same); validated at construction."""

    minimum_travel_distance: float = 0.2  # [m] slam_toolbox: 0.5
    minimum_travel_heading: float = 0.3  # [rad] slam_toolbox: 0.5
    scan_buffer_size: int = 10  # keyframes in the local submap
    scan_buffer_maximum_scan_distance: float = 10.0  # [m] farthest keyframe of the local submap
    correlation_search_space_dimension: float = 0.6  # [m] full width of the link search window
    coarse_search_angle_offset: float = 0.35  # [rad] ± heading of the link and loop searches
    link_match_minimum_response_fine: float = 0.3  # [-] below this the odometry links the keyframe
    odometry_sigma_per_meter: float = 0.05  # [m/m] odometry edge std per metre driven (+ 1 cm)
    odometry_sigma_yaw_per_radian: float = 0.05  # [rad/rad] odometry edge heading std per radian turned (+ 0.01)
    do_loop_closing: bool = True
    loop_search_maximum_distance: float = 3.0  # [m] old keyframes this close to the new pose are candidates ...
    loop_minimum_travel: float = 5.0  # [m] ... if the robot has driven this far since
    loop_match_minimum_chain_size: int = 7  # keyframes in a loop-candidate submap
    loop_search_space_dimension: float = 2.0  # [m] full width of the loop search window
    loop_match_minimum_response_fine: float = 0.6  # [-]
    loop_match_uniqueness_radius: float = 0.5  # [m] a second peak this far away ...
    loop_match_uniqueness_ratio: float = 0.85  # [-] ... must score below this fraction of the best
    loop_match_agreement_distance: float = 0.15  # [m] the reverse match must agree this well
    loop_closure_cooldown: int = 3  # keyframes after an accepted closure before the next search

    def __post_init__(self) -> None:
        owner = "mapper"
        for name in ("minimum_travel_distance", "minimum_travel_heading", "scan_buffer_maximum_scan_distance",
                     "correlation_search_space_dimension", "coarse_search_angle_offset",
                     "odometry_sigma_per_meter", "odometry_sigma_yaw_per_radian", "loop_search_maximum_distance",
                     "loop_minimum_travel", "loop_search_space_dimension", "loop_match_uniqueness_radius",
                     "loop_match_agreement_distance"):
            validation.number(owner, name, getattr(self, name), minimum=0.0)
        for name in ("link_match_minimum_response_fine", "loop_match_minimum_response_fine",
                     "loop_match_uniqueness_ratio"):
            validation.number(owner, name, getattr(self, name), minimum=0.0, maximum=1.0)
        validation.integer(owner, "scan_buffer_size", self.scan_buffer_size, minimum=1)
        validation.integer(owner, "loop_match_minimum_chain_size", self.loop_match_minimum_chain_size, minimum=1)
        validation.integer(owner, "loop_closure_cooldown", self.loop_closure_cooldown, minimum=0)
        if not isinstance(self.do_loop_closing, bool):
            raise ConfigError(f"{owner}: do_loop_closing must be true or false, got {self.do_loop_closing!r}")


class Keyframe(NamedTuple):
    odom: Pose2D  # [m, m, rad] odometry pose when the scan was taken
    rays: ScanRays  # the scan, robot frame
    travel: float  # [m] driven (by odometry) from the first keyframe to this one
    stamp: float = math.nan  # [s] the scan's stamp (ROS time); NaN when the caller gave none


class LoopClosure(NamedTuple):
    old: int  # keyframe index
    new: int  # keyframe index
    response: float  # [-]
    second: float  # [-] best response outside the uniqueness radius (0 if none)


class GraphSlam:
    """The keyframes, their pose graph and the map built from them. Not thread-safe (a node holds a lock)."""

    def __init__(
        self, params: Optional[SlamParams] = None, occupancy: Optional[OccupancyParams] = None,
        matcher: Optional[MatcherParams] = None, *, map_start_pose: Optional[Pose2D] = None,
    ) -> None:
        """``map_start_pose`` (x [m], y [m], yaw [rad]): where the first keyframe sits in the map frame (None: at its
        odometry pose)."""
        self.params = params or SlamParams()
        self.map_start_pose = None if map_start_pose is None else _finite(map_start_pose, "map_start_pose")
        self.occupancy = occupancy or OccupancyParams()
        self.matcher = ScanMatcher(matcher or MatcherParams())
        self.graph = PoseGraph()
        self.keyframes: List[Keyframe] = []
        self.loop_closures: List[LoopClosure] = []
        self.rejected_loops = 0  # candidate closures that failed a check
        self._cooldown = 0
        self._reanchor = False  # the odometry broke off: the next scan is placed by matching alone
        self._map: Optional[GridMap] = None  # cached until the keyframes or their poses change

    # --- per scan ----------------------------------------------------------------------------------------------
    def add_scan(self, odom: Pose2D, scan: ScanBeams, stamp_s: float = math.nan) -> bool:
        """Take a scan stamped ``stamp_s`` [s] with the robot at ``odom`` (odometry frame); True when it became a
        keyframe (the stamp is kept with it, to compare the optimised trajectory with a ground truth).
        :class:`ConfigError` for a non-finite odometry pose or a malformed scan (the graph is left as it was)."""
        odom = _finite(odom)
        rays = _rays(scan, self.occupancy.max_free_range)
        if not self.keyframes:
            start = odom if self.map_start_pose is None else self.map_start_pose
            self._append(odom, rays, start, np.diag([1e-4, 1e-4, 1e-4]), kind=EdgeKind.ODOMETRY, travel=0.0,
                         stamp_s=stamp_s)
            return True
        if self._reanchor:
            return self._add_reanchored(odom, rays, stamp_s)
        last = self.keyframes[-1]
        step = compose_poses(inverse_pose(last.odom), odom)
        distance = math.hypot(step[0], step[1])
        p = self.params
        if distance < p.minimum_travel_distance and abs(step[2]) < p.minimum_travel_heading:
            return False
        previous = self.graph.pose(len(self.keyframes) - 1)
        predicted = compose_poses(previous, step)
        match = self._link(predicted, rays)
        if match is not None:
            pose, covariance, kind = match.pose, match.covariance, EdgeKind.SCAN_MATCH
        else:
            sigma_xy = 0.01 + p.odometry_sigma_per_meter * distance
            sigma_yaw = 0.01 + p.odometry_sigma_yaw_per_radian * abs(step[2]) + 0.02 * distance
            pose, covariance, kind = predicted, np.diag([sigma_xy**2, sigma_xy**2, sigma_yaw**2]), EdgeKind.ODOMETRY
        self._append(odom, rays, pose, covariance, kind=kind, travel=last.travel + distance, stamp_s=stamp_s)
        if p.do_loop_closing:
            self._close_loop()
        return True

    def restart_odometry(self) -> None:
        """Forget the odometry the keyframes were taken with (it jumped, time went back, or the mapping goes on in
        a new run after :meth:`from_dict`): the next scans are placed by matching them against the last keyframes'
        submap over the loop-search window (``loop_search_space_dimension``, ± twice
        ``coarse_search_angle_offset``) around the last keyframe, so the robot must be within that of where the
        mapping stopped; until one fits (``loop_match_minimum_response_fine``) scans are not used."""
        self._reanchor = bool(self.keyframes)

    @property
    def reanchoring(self) -> bool:
        """True while scans wait to be placed after :meth:`restart_odometry`."""
        return self._reanchor

    def _add_reanchored(self, odom: Pose2D, rays: ScanRays, stamp_s: float) -> bool:
        p = self.params
        last = len(self.keyframes) - 1
        chain = list(range(max(0, last - p.scan_buffer_size + 1), last + 1))
        window = Window(self.graph.pose(last), p.loop_search_space_dimension / 2.0, 2.0 * p.coarse_search_angle_offset)
        lookup = self.matcher.lookup(self._points(chain), self._lookup_margin(window))
        unique = self._unique_match(lookup, _hits(rays), window)
        if unique is None:
            return False
        match = unique[0]
        self._append(odom, rays, match.pose, match.covariance, kind=EdgeKind.SCAN_MATCH,
                     travel=self.keyframes[last].travel + _distance(self.graph.pose(last), match.pose), stamp_s=stamp_s)
        self._reanchor = False
        return True

    def _append(self, odom: Pose2D, rays: ScanRays, pose: Pose2D, covariance: np.ndarray, *, kind: EdgeKind,
                travel: float, stamp_s: float) -> None:
        index = self.graph.add_node(pose)
        if index > 0:
            previous = self.graph.pose(index - 1)
            self.graph.add_edge(index - 1, index, compose_poses(inverse_pose(previous), pose), covariance, kind)
        self.keyframes.append(Keyframe(odom, rays, travel, float(stamp_s)))
        self._map = None

    def _link(self, predicted: Pose2D, rays: ScanRays) -> Optional[Match]:
        p = self.params
        last = len(self.keyframes) - 1
        chain = [i for i in range(max(0, last - p.scan_buffer_size + 1), last + 1)
                 if _distance(self.graph.pose(i), predicted) <= p.scan_buffer_maximum_scan_distance]
        match = self._match(chain, rays, Window(predicted, p.correlation_search_space_dimension / 2.0,
                                                p.coarse_search_angle_offset))
        if match is None or match.response < p.link_match_minimum_response_fine:
            return None
        return match

    # --- loops -------------------------------------------------------------------------------------------------
    def _close_loop(self) -> None:
        p = self.params
        if self._cooldown > 0:
            self._cooldown -= 1
            return
        new = len(self.keyframes) - 1
        travel = np.array([k.travel for k in self.keyframes[:new]])
        poses = self.graph.poses()
        distance = np.hypot(poses[:new, 0] - poses[new, 0], poses[:new, 1] - poses[new, 1])
        candidate = (self.keyframes[new].travel - travel >= p.loop_minimum_travel) & (
            distance <= p.loop_search_maximum_distance)
        if not candidate.any():
            return
        old = int(np.argmin(np.where(candidate, distance, np.inf)))
        closure = self._verified_closure(old, new)
        if closure is None:
            self.rejected_loops += 1
            return
        self.loop_closures.append(closure[0])
        self.graph.add_edge(old, new, closure[1], closure[2], EdgeKind.LOOP)
        self.graph.optimize()
        self._map = None
        self._cooldown = p.loop_closure_cooldown

    def _verified_closure(self, old: int, new: int) -> Optional[Tuple[LoopClosure, Pose2D, np.ndarray]]:
        """The closure between keyframes ``old`` and ``new`` (the relative pose and its covariance) if it passes
        every check of the module docstring, else None."""
        p = self.params
        half = p.loop_match_minimum_chain_size // 2
        chain = list(range(max(0, old - half), min(old + half + 1, new)))
        rays = self.keyframes[new].rays
        window = Window(self.graph.pose(new), p.loop_search_space_dimension / 2.0, p.coarse_search_angle_offset)
        lookup = self.matcher.lookup(self._points(chain), self._lookup_margin(window))
        unique = self._unique_match(lookup, _hits(rays), window)
        if unique is None:
            return None
        match, second_response = unique
        relative = compose_poses(inverse_pose(self.graph.pose(old)), match.pose)
        # the other way: the old scan against the new keyframe's neighbourhood placed where the match put the new
        # keyframe; it must come back to the old keyframe's pose
        new_pose = self.graph.pose(new)
        moved = {i: compose_poses(match.pose, compose_poses(inverse_pose(new_pose), self.graph.pose(i)))
                 for i in range(max(0, new - 2 * half), new + 1)}
        back_window = Window(self.graph.pose(old), 2 * p.loop_match_agreement_distance,
                             p.coarse_search_angle_offset / 2.0)
        back_lookup = self.matcher.lookup(self._points(list(moved), corrected=moved),
                                          self._lookup_margin(back_window))
        back = self.matcher.match(back_lookup, _hits(self.keyframes[old].rays), back_window)
        if back is None or _distance(back.pose, back_window.prior) > p.loop_match_agreement_distance:
            return None
        closure = LoopClosure(old, new, match.response, second_response)
        return closure, relative, match.covariance

    def _lookup_margin(self, window: Window) -> float:
        """[m] around the reference points, the lookup table must reach: a point farther from every reference point
        than a few ``sigma`` scores nothing wherever it falls, so the table needs the window's reach and that."""
        return window.xy + LOOKUP_SIGMAS * self.matcher.params.sigma

    def _unique_match(self, lookup: Lookup, points: np.ndarray, window: Window) -> Optional[Tuple[Match, float]]:
        """The best match of ``points`` in ``window`` and the best response outside ``loop_match_uniqueness_radius``
        of it, if the first reaches ``loop_match_minimum_response_fine`` and the second stays below
        ``loop_match_uniqueness_ratio`` of it; else None (no fit, or the scene repeats within the window)."""
        p = self.params
        match = self.matcher.match(lookup, points, window)
        if match is None or match.response < p.loop_match_minimum_response_fine:
            return None
        second = self.matcher.match(lookup, points, window,
                                    exclude=(match.pose, p.loop_match_uniqueness_radius, math.pi))
        second_response = 0.0 if second is None else second.response
        if second_response >= p.loop_match_uniqueness_ratio * match.response:
            return None
        return match, second_response

    # --- maps and frames ---------------------------------------------------------------------------------------
    def _points(self, indices: List[int], corrected: Optional[Dict[int, Pose2D]] = None) -> np.ndarray:
        """The hits of keyframes ``indices`` in the map frame, each at its graph pose (or ``corrected[i]``)."""
        chunks = []
        for i in indices:
            pose = (corrected or {}).get(i, self.graph.pose(i))
            chunks.append(transform_poses(_hits(self.keyframes[i].rays), *pose))
        return np.vstack(chunks) if chunks else np.zeros((0, 2))

    def _match(self, chain: List[int], rays: ScanRays, window: Window) -> Optional[Match]:
        if not chain:
            return None
        lookup = self.matcher.lookup(self._points(chain), self._lookup_margin(window))
        return self.matcher.match(lookup, _hits(rays), window)

    def poses(self) -> np.ndarray:
        """(N, 3) the keyframes' optimised poses [m, m, rad], map frame."""
        return self.graph.poses()

    def map_to_odom(self) -> Pose2D:
        """The transform map → odom implied by the last keyframe (identity before the first)."""
        if not self.keyframes:
            return (0.0, 0.0, 0.0)
        last = len(self.keyframes) - 1
        return compose_poses(self.graph.pose(last), inverse_pose(self.keyframes[last].odom))

    def occupancy_map(self) -> GridMap:
        """The occupancy grid of every keyframe at its optimised pose (rebuilt when they changed)."""
        if self._map is None:
            poses = [tuple(float(v) for v in row) for row in self.poses()]
            grid = rasterize(self.occupancy, poses, [k.rays for k in self.keyframes])  # type: ignore[arg-type]
            self._map = grid.to_grid_map()
        return self._map

    # --- files -------------------------------------------------------------------------------------------------
    def to_dict(self) -> Dict[str, Any]:
        """The keyframes (odometry, rays) and the pose graph as plain JSON-able values (``~serialize_map``)."""
        return {
            "format": "flex_nav.mapping.posegraph/1",
            "keyframes": [
                {"odom": list(k.odom), "origin": list(k.rays.origin), "end_x": k.rays.end_x.tolist(),
                 "end_y": k.rays.end_y.tolist(), "hit": k.rays.hit.astype(int).tolist(), "travel": k.travel,
                 "stamp": k.stamp if math.isfinite(k.stamp) else None}
                for k in self.keyframes
            ],
            "loop_closures": [list(c) for c in self.loop_closures],
            "graph": self.graph.to_dict(),
        }

    @classmethod
    def from_dict(
        cls, data: Dict[str, Any], params: Optional[SlamParams] = None, occupancy: Optional[OccupancyParams] = None,
        matcher: Optional[MatcherParams] = None,
    ) -> GraphSlam:
        """A mapper continuing from :meth:`to_dict`'s output; :class:`ConfigError` naming what is malformed."""
        if not isinstance(data, dict) or data.get("format") != "flex_nav.mapping.posegraph/1":
            raise ConfigError("mapper: not a flex_nav pose graph (format flex_nav.mapping.posegraph/1 expected)")
        slam = cls(params, occupancy, matcher)
        try:
            for k in data["keyframes"]:
                rays = ScanRays((float(k["origin"][0]), float(k["origin"][1])), np.asarray(k["end_x"], dtype=float),
                                np.asarray(k["end_y"], dtype=float), np.asarray(k["hit"], dtype=bool))
                if not (rays.end_x.shape == rays.end_y.shape == rays.hit.shape):
                    raise ConfigError("mapper: a keyframe's end_x, end_y and hit differ in length")
                stamp = k.get("stamp")  # absent in files written before stamps were kept
                slam.keyframes.append(Keyframe(_finite(tuple(k["odom"])), rays, float(k["travel"]),
                                               math.nan if stamp is None else float(stamp)))
            slam.loop_closures = [LoopClosure(int(c[0]), int(c[1]), float(c[2]), float(c[3]))
                                  for c in data["loop_closures"]]
            slam.graph = PoseGraph.from_dict(data["graph"])
        except (KeyError, TypeError, ValueError, IndexError) as err:
            raise ConfigError(f"mapper: malformed pose graph file: {err!r}") from err
        if slam.graph.node_count != len(slam.keyframes):
            raise ConfigError(f"mapper: the graph has {slam.graph.node_count} nodes but the file "
                              f"{len(slam.keyframes)} keyframes")
        return slam


def _finite(pose: Any, what: str = "odometry pose") -> Pose2D:
    x, y, yaw = validation.planar_pose("mapper", what, pose)
    return x, y, wrap_angle(yaw)


def _rays(scan: ScanBeams, max_free_range: float) -> ScanRays:
    ranges = np.asarray(scan.ranges, dtype=np.float64).ravel()
    angles = np.asarray(scan.angles, dtype=np.float64).ravel()
    if ranges.shape != angles.shape:
        raise ConfigError(f"mapper: scan has {ranges.size} ranges but {angles.size} angles")
    if not (math.isfinite(scan.range_min) and math.isfinite(scan.range_max) and 0.0 <= scan.range_min
            < scan.range_max):
        raise ConfigError(f"mapper: scan needs 0 <= range_min < range_max, got {scan.range_min!r}, "
                          f"{scan.range_max!r}")
    return scan_rays(scan, max_free_range)


def _hits(rays: ScanRays) -> np.ndarray:
    return np.column_stack([rays.end_x[rays.hit], rays.end_y[rays.hit]])


def _distance(a: Pose2D, b: Pose2D) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def warm_up() -> float:
    """Run every compiled kernel of the mapper once (ray tracing, the scan matcher's branch and bound), so that numba
    compiles them into its cache (or loads them from it); returns the wall time it took [s]. For an installer."""
    import time  # noqa: PLC0415 - only here

    started = time.monotonic()
    angles = np.linspace(-2.0, 2.0, 90)
    ranges = np.where(np.abs(angles) < 1.0, 2.0 / np.maximum(np.cos(angles), 0.5), 3.0)  # a wall 2 m ahead
    slam = GraphSlam()
    for x in (0.0, 0.25):
        slam.add_scan((x, 0.0, 0.0), ScanBeams(ranges, angles, (0.0, 0.0, 0.0), 0.05, 5.0))
    slam.occupancy_map()
    return time.monotonic() - started
