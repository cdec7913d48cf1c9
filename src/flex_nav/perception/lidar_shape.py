"""The lidar's view of the object blocking the way: box-like (straight faces, corners) or person-like (it moves;
optionally two leg arcs, a round body), with a confidence and the features it was decided from.

The camera decides what an object is from its colour and texture, from one viewpoint; a planar lidar sees the
object's outline in its plane whatever its colour: a box shows one straight face or two faces meeting at a
right angle, a person two small leg arcs (a leg scanner's height) or one round body (a torso or a capsule).

The scan's end points are cut into clusters as the moving-obstacle tracker cuts them
(:func:`flex_nav.perception.scan_segments.split_points`: neighbours closer than ``gap_m + gap_per_m * range``
[m] belong together, a beam without a return separates), but no cluster is dropped for being wide. The
*object* is the cluster with the hit nearest to ``target`` (a point on the robot's path where it was blocked),
if that hit lies within ``search_radius_m`` [m]. Its outline is fitted three ways, each residual given as an
RMS with the degrees of freedom of its fit taken off (so a model with more parameters does not win on noise):

- one straight line (total least squares);
- a corner: two lines meeting at one of the hits (the best split; each side at least 3 hits);
- a circle (algebraic fit): its radius, and whether it bulges toward the sensor (a body) or away (a hollow).

The range noise expected at the object's mean range is ``noise_m + noise_per_m * range`` [m] (one sigma).
The label, first rule that applies:

1. ``none``: no hit within ``search_radius_m`` of the target;
2. ``person``: the object moves (``speed_mps`` from a track, at least ``moving_speed_mps``): boxes stand still;
3. the object is leg-sized (``leg_min_width_m`` to ``leg_max_width_m`` across) and another leg-sized cluster
   lies within ``leg_pair_max_gap_m`` of it with the background seen between them (at least one beam between
   the two that has no return or ends farther: two pieces of one box's outline are neighbouring beams): two
   static legs, ``person`` if ``two_legs_person``, else ``unsure``; one leg-sized arc alone that is curved (at
   least 3 hits, bulging toward the sensor, a circle of at most leg size fitting ``curvature_ratio`` times
   better than a line, the line above the noise): ``person`` if ``lone_leg_person``, else ``unsure``; one not
   clearly curved: ``unsure``;
4. fewer than ``min_points`` hits: ``unsure`` (too few to tell a corner from a curve);
5. a static round body: the circle bulges toward the sensor, its radius is in [``body_min_radius_m``,
   ``body_max_radius_m``], the single line does not fit within the noise, and the circle's residual is at most
   ``curvature_ratio`` times that of the best box outline (the line, or the corner if its angle is within 20
   degrees of a right angle: a curve cut in two makes a blunter one): ``person`` if ``round_body_person``, else
   ``unsure``;
6. a box outline (the line, or a right-angled corner, fits within ``straight_sigmas`` noise sigmas):
   ``box`` if it is ``box_min_size_m`` to ``box_max_size_m`` [m] across (larger: a wall or furniture, smaller:
   too little to tell, both ``unsure``); a right corner (0.9) or a face of at least 12 hits (0.85) gives more
   confidence than a short straight outline (0.7);
7. otherwise ``unsure``.

By default (since 2026-11-29) only a moving object is a ``person``: ``two_legs_person``, ``lone_leg_person`` and
``round_body_person`` are off, so two static leg-like arcs, a lone curved arc and a static round body are
``unsure`` (``leg_min_width_m`` 0). On the classifier's validation scenes a static person-like outline was as often a
drum, a bin, a bag, a plant or a chair's or table's legs as a person; of 18 candidate lidar cues and fusion rules
this one was chosen there by a criterion stated before scoring (``tools/perception/evaluate_fused.py``: "Choosing a
rule"; figures in ``models/README.md``). Switch them on for a lidar that sees people's legs better than it sees such
look-alikes.

The same outline rules, without motion, tell which tracks of the moving-obstacle tracker are boxes
(:func:`box_outlines`, :func:`without_boxes`): the tracker keeps anything small enough that the static map does
not explain, so a box the robot has just pushed is a standing "person" to the social distance rule, which then
kept the robot from the way past it (S4, every seed, with the rule on).

Pure numpy, no ROS, no clock: the caller passes points in one planar frame (e.g. the laser's), the sensor's
position in it, and the track speed if the object is tracked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError
from flex_nav.perception.moving_obstacles import Track
from flex_nav.perception.scan_segments import SegmentParams, split_points

BOX = "box"
PERSON = "person"
UNSURE = "unsure"
NONE = "none"
LIDAR_LABELS: Tuple[str, ...] = (BOX, PERSON, UNSURE, NONE)

MIN_SIDE_POINTS = 3  # hits on each side of a corner fit
RIGHT_ANGLE_TOLERANCE_DEG = 20.0  # [deg] a corner this close to 90 degrees is a box's corner
LONG_FACE_POINTS = 12  # a straight face of this many hits is clearly straight


@dataclass(frozen=True)
class ShapeParams:
    """Parameters of :func:`classify_shape`; units in comments."""

    gap_m: float = 0.12  # [m] neighbouring hits closer than this belong to one cluster (at short range)
    gap_per_m: float = 0.04  # [m per m of range] added to gap_m
    search_radius_m: float = 0.6  # [m] the object is the cluster with a hit this close to the target
    min_points: int = 8  # fewer hits (not a leg): unsure (too little to tell a corner from a curve)
    noise_m: float = 0.002  # [m] range noise (one sigma) at 0 m
    noise_per_m: float = 0.005  # [m per m of range] noise growing with range (TurtleBot 4's RPLidar A1: 0.5 %)
    straight_sigmas: float = 1.8  # a straight outline fits within this many noise sigmas
    curvature_ratio: float = 0.6  # a circle this much better than the straight outline is a round body
    leg_max_width_m: float = 0.2  # [m] a leg is at most this wide
    leg_pair_max_gap_m: float = 0.5  # [m] two legs' centres at most this far apart
    body_min_radius_m: float = 0.1  # [m] round body (torso, capsule) radius range
    body_max_radius_m: float = 0.4  # [m]
    box_min_size_m: float = 0.2  # [m] a straight object smaller than this: unsure
    box_max_size_m: float = 1.6  # [m] a straight object larger than this: a wall or furniture (unsure)
    moving_speed_mps: float = 0.2  # [m/s] a tracked object at least this fast moves
    leg_min_width_m: float = 0.0  # [m] a leg is at least this wide (0: any; a chair's or table's leg is thinner)
    two_legs_person: bool = False  # two static leg-sized arcs are a person (False: unsure)
    lone_leg_person: bool = False  # one static curved leg-sized arc is a person (False: unsure)
    round_body_person: bool = False  # a static round body is a person (False: unsure)

    def __post_init__(self) -> None:
        owner = "lidar shape"
        for name in ("gap_m", "search_radius_m", "noise_m", "straight_sigmas", "leg_max_width_m",
                     "leg_pair_max_gap_m", "body_min_radius_m", "body_max_radius_m", "box_min_size_m",
                     "box_max_size_m", "moving_speed_mps"):
            validation.number(owner, name, getattr(self, name), positive=True)
        validation.number(owner, "gap_per_m", self.gap_per_m, minimum=0.0)
        validation.number(owner, "noise_per_m", self.noise_per_m, minimum=0.0)
        validation.number(owner, "curvature_ratio", self.curvature_ratio, positive=True, maximum=1.0)
        validation.integer(owner, "min_points", self.min_points, minimum=MIN_SIDE_POINTS)
        validation.number(owner, "body_max_radius_m", self.body_max_radius_m, minimum=self.body_min_radius_m)
        validation.number(owner, "box_max_size_m", self.box_max_size_m, minimum=self.box_min_size_m)
        validation.number(owner, "leg_min_width_m", self.leg_min_width_m, minimum=0.0, maximum=self.leg_max_width_m)
        for name in ("two_legs_person", "lone_leg_person", "round_body_person"):
            validation.boolean(owner, name, getattr(self, name))

    def noise_at(self, range_m: float) -> float:
        """Expected range noise (one sigma) [m] at ``range_m`` [m]."""
        return self.noise_m + self.noise_per_m * range_m


@dataclass(frozen=True)
class ShapeFeatures:
    """What the outline of the object looks like (NaN where a fit was impossible)."""

    points: int  # hits on the object
    range_m: float  # [m] nearest hit from the sensor
    size_m: float  # [m] largest extent of the hits
    line_rms_m: float  # [m] residual of one straight line
    corner_rms_m: float  # [m] residual of the best corner (two lines), NaN with too few hits
    corner_angle_deg: float  # [deg] angle between the corner's two lines in [0, 90], NaN without a corner
    circle_rms_m: float  # [m] residual of the circle fit
    circle_radius_m: float  # [m] its radius (inf for collinear hits)
    bulges: bool  # the circle's centre lies behind the hits (seen from the sensor): a body, not a hollow
    noise_m: float  # [m] expected range noise (one sigma) at the object's mean range
    legs: int  # leg-sized clusters making up the object (0, 1 or 2)
    speed_mps: Optional[float]  # [m/s] tracked speed, None if not tracked
    centre: Tuple[float, float]  # [m] mean of the hits (the frame of the points)

    def summary(self) -> str:
        """One line of the features, e.g. ``12 hits at 0.55 m, 0.41 m across, line rms 4 mm, ...``."""
        speed = "untracked" if self.speed_mps is None else f"speed {self.speed_mps:.2f} m/s"
        return (f"{self.points} hits at {self.range_m:.2f} m, {self.size_m:.2f} m across, line rms "
                f"{1000 * self.line_rms_m:.0f} mm, corner rms {1000 * self.corner_rms_m:.0f} mm at "
                f"{self.corner_angle_deg:.0f} deg, circle r {self.circle_radius_m:.2f} m rms "
                f"{1000 * self.circle_rms_m:.0f} mm{' (bulging)' if self.bulges else ''}, noise "
                f"{1000 * self.noise_m:.0f} mm, legs {self.legs}, {speed}")


@dataclass(frozen=True)
class ShapeCue:
    """The lidar's cue: a label of :data:`LIDAR_LABELS`, a confidence [0..1], why, and the features."""

    label: str
    confidence: float
    reason: str
    features: Optional[ShapeFeatures] = None

    def describe(self) -> str:
        """``box 0.90 (corner of 88 deg within the noise): 25 hits at ...``."""
        head = f"{self.label} {self.confidence:.2f} ({self.reason})"
        return head if self.features is None else f"{head}: {self.features.summary()}"


# ---------------------------------------------------------------------------------------------- fits
def _line_ssr(xs: np.ndarray, ys: np.ndarray) -> Tuple[float, float]:
    """(sum of squared perpendicular residuals [m^2], direction [rad]) of the total-least-squares line."""
    ssr, angle = _prefix_line_fits(xs, ys)
    return float(ssr[-1]), float(angle[-1])


def _prefix_line_fits(xs: np.ndarray, ys: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """For every prefix xs[:k + 1]: the TLS line's sum of squared residuals and direction [rad] (from running
    sums; a prefix of one point has residual 0)."""
    count = np.arange(1, len(xs) + 1, dtype=np.float64)
    mx, my = np.cumsum(xs) / count, np.cumsum(ys) / count
    sxx = np.cumsum(xs * xs) / count - mx * mx
    syy = np.cumsum(ys * ys) / count - my * my
    sxy = np.cumsum(xs * ys) / count - mx * my
    half_trace = 0.5 * (sxx + syy)
    spread = np.sqrt(np.maximum(0.0, 0.25 * (sxx - syy) ** 2 + sxy * sxy))
    smallest = np.maximum(0.0, half_trace - spread)
    return count * smallest, 0.5 * np.arctan2(2.0 * sxy, sxx - syy)


def _corner_fit(xs: np.ndarray, ys: np.ndarray) -> Tuple[float, float]:
    """(RMS [m], angle between the lines [deg] in [0, 90]) of the best two-line fit sharing one hit; NaN if the
    hits are too few for both sides."""
    count = len(xs)
    if count < 2 * MIN_SIDE_POINTS - 1:
        return math.nan, math.nan
    head_ssr, head_angle = _prefix_line_fits(xs, ys)
    tail_ssr_rev, tail_angle_rev = _prefix_line_fits(xs[::-1], ys[::-1])
    splits = np.arange(MIN_SIDE_POINTS - 1, count - MIN_SIDE_POINTS + 1)  # the shared hit's index
    total = head_ssr[splits] + tail_ssr_rev[count - 1 - splits]
    best = int(np.argmin(total))
    split = int(splits[best])
    dof = max(1, count + 1 - 4)
    rms = math.sqrt(float(total[best]) / dof)
    diff = abs(float(head_angle[split]) - float(tail_angle_rev[count - 1 - split])) % math.pi
    angle = math.degrees(min(diff, math.pi - diff))
    return rms, angle


def _circle_fit(xs: np.ndarray, ys: np.ndarray) -> Tuple[float, float, float, float]:
    """(centre x, centre y, radius, RMS) [m] of the algebraic circle fit; radius inf for collinear hits."""
    design = np.column_stack((xs, ys, np.ones_like(xs)))
    rhs = -(xs * xs + ys * ys)
    solution, _res, rank, _sv = np.linalg.lstsq(design, rhs, rcond=None)
    if rank < 3:
        return math.nan, math.nan, math.inf, math.inf
    cx, cy = -0.5 * float(solution[0]), -0.5 * float(solution[1])
    radius_sq = cx * cx + cy * cy - float(solution[2])
    if not math.isfinite(radius_sq) or radius_sq <= 0.0:
        return math.nan, math.nan, math.inf, math.inf
    radius = math.sqrt(radius_sq)
    residual = np.hypot(xs - cx, ys - cy) - radius
    dof = max(1, len(xs) - 3)
    return cx, cy, radius, math.sqrt(float(np.sum(residual * residual)) / dof)


# ---------------------------------------------------------------------------------------------- clusters
def clusters(xs: np.ndarray, ys: np.ndarray, sensor: Tuple[float, float], params: ShapeParams, *,
             wrap: bool = True) -> List[np.ndarray]:
    """Index arrays (into ``xs``, in beam order) of the clusters of a scan's end points (NaN: no return, which
    always separates); no cluster is dropped for its width. ``wrap``: the scan covers 360 degrees, so a cluster
    across its seam (last beam next to the first) is one cluster, its indices running on from the last to 0."""
    xs = np.asarray(xs, dtype=np.float64)
    ys = np.asarray(ys, dtype=np.float64)
    if xs.shape != ys.shape or xs.ndim != 1:
        raise ConfigError(f"scan points need two 1-D arrays of one length, got shapes {xs.shape} and {ys.shape}")
    finite = np.isfinite(xs) & np.isfinite(ys)
    bounds = np.flatnonzero(np.diff(np.concatenate(([0], finite.astype(np.int8), [0]))))
    seg_params = SegmentParams(gap_m=params.gap_m, gap_per_m=params.gap_per_m)
    out: List[np.ndarray] = []
    for start, stop in zip(bounds[::2], bounds[1::2]):
        px, py = xs[start:stop], ys[start:stop]
        ranges = np.hypot(px - sensor[0], py - sensor[1])
        out.extend(run + start for run in split_points(px, py, ranges, seg_params, False))
    count = len(xs)
    if wrap and len(out) > 1 and out[0][0] == 0 and out[-1][-1] == count - 1:
        reach = max(math.hypot(xs[0] - sensor[0], ys[0] - sensor[1]), math.hypot(xs[-1] - sensor[0],
                                                                                  ys[-1] - sensor[1]))
        if math.hypot(xs[0] - xs[-1], ys[0] - ys[-1]) <= params.gap_m + params.gap_per_m * reach:
            out = [np.concatenate((out[-1], out[0])), *out[1:-1]]
    return out


def object_speed(tracks: Sequence[Track], centre: Tuple[float, float], max_distance_m: float) -> Optional[float]:
    """Speed [m/s] of the track nearest to ``centre`` (x, y) [m] if one lies within ``max_distance_m`` [m]."""
    best: Optional[Tuple[float, float]] = None
    for track in tracks:
        distance = math.hypot(track.x - centre[0], track.y - centre[1])
        if distance <= max_distance_m and (best is None or distance < best[0]):
            best = (distance, track.speed)
    return None if best is None else best[1]


# ---------------------------------------------------------------------------------------------- classifier
def _size(px: np.ndarray, py: np.ndarray) -> float:
    points = np.column_stack((px, py))
    if len(points) > 64:  # the extent from a subsample's pairs: a few hits less never change it by a beam
        points = points[np.linspace(0, len(points) - 1, 64).astype(np.int64)]
    diff = points[:, None, :] - points[None, :, :]
    return float(np.sqrt((diff * diff).sum(axis=2).max()))


def features_of(px: np.ndarray, py: np.ndarray, sensor: Tuple[float, float], params: ShapeParams, *,
                legs: int = 0, speed_mps: Optional[float] = None) -> ShapeFeatures:
    """The outline features of one object's hits (``px``, ``py`` [m], beam order) seen from ``sensor``."""
    px = np.asarray(px, dtype=np.float64)
    py = np.asarray(py, dtype=np.float64)
    count = len(px)
    ranges = np.hypot(px - sensor[0], py - sensor[1])
    mx, my = float(px.mean()), float(py.mean())
    line_ssr, _ = _line_ssr(px - mx, py - my)
    line_rms = math.sqrt(line_ssr / max(1, count - 2))
    corner_rms, corner_angle = _corner_fit(px - mx, py - my)
    cx, cy, radius, circle_rms = _circle_fit(px - mx, py - my) if count >= 3 else (
        math.nan, math.nan, math.inf, math.inf)
    bulges = bool(math.isfinite(radius) and math.hypot(cx + mx - sensor[0], cy + my - sensor[1])
                  > math.hypot(mx - sensor[0], my - sensor[1]))
    return ShapeFeatures(count, float(ranges.min()), _size(px, py), line_rms, corner_rms, corner_angle, circle_rms,
                         radius, bulges, params.noise_at(float(ranges.mean())), legs, speed_mps, (mx, my))


def _leg_sized(px: np.ndarray, py: np.ndarray, params: ShapeParams) -> bool:
    return params.leg_min_width_m <= _size(px, py) <= params.leg_max_width_m


def _seen_between(xs: np.ndarray, ys: np.ndarray, sensor: Tuple[float, float], first: np.ndarray,
                  second: np.ndarray) -> bool:
    """True if the beams between two clusters (beam order, the shorter way round) look past them: at least one
    beam, each without a return or ending farther than the nearer cluster. Two legs show the background between
    them; two pieces of one box's outline (cut where a face is seen at a grazing angle) are neighbouring beams."""
    count = len(xs)
    after_first = (int(second[0]) - int(first[-1]) - 1) % count  # beams from the end of first to second
    after_second = (int(first[0]) - int(second[-1]) - 1) % count
    if after_first <= after_second:
        between = (int(first[-1]) + 1 + np.arange(after_first)) % count
    else:
        between = (int(second[-1]) + 1 + np.arange(after_second)) % count
    if len(between) == 0:
        return False
    nearer = min(float(np.hypot(xs[c] - sensor[0], ys[c] - sensor[1]).mean()) for c in (first, second))
    ranges = np.hypot(xs[between] - sensor[0], ys[between] - sensor[1])
    return bool(np.all(~np.isfinite(ranges) | (ranges > nearer)))


def classify_shape(xs: np.ndarray, ys: np.ndarray, sensor: Tuple[float, float], target: Tuple[float, float],
                   params: Optional[ShapeParams] = None, *, speed_mps: Optional[float] = None,
                   wrap: bool = True) -> ShapeCue:
    """The lidar cue of the object nearest to ``target`` (x, y) [m] in a scan's end points (``xs``, ``ys`` [m],
    beam order, NaN: no return) seen from ``sensor`` (x, y) [m]; ``speed_mps`` [m/s]: the object's tracked
    speed, None if it is not tracked; ``wrap``: the scan covers 360 degrees (its last beam next to its first).
    See the module docstring for the rules."""
    params = params if params is not None else ShapeParams()
    xs = np.asarray(xs, dtype=np.float64)
    ys = np.asarray(ys, dtype=np.float64)
    found = clusters(xs, ys, sensor, params, wrap=wrap)
    best: Optional[Tuple[float, int]] = None
    for index, run in enumerate(found):
        distance = float(np.hypot(xs[run] - target[0], ys[run] - target[1]).min())
        if distance <= params.search_radius_m and (best is None or distance < best[0]):
            best = (distance, index)
    if best is None:
        return ShapeCue(NONE, 1.0, f"no hit within {params.search_radius_m:.2f} m of the target")
    run = found[best[1]]
    px, py = xs[run], ys[run]
    legs = 0
    if _leg_sized(px, py, params):
        legs = 1
        centre = np.array([px.mean(), py.mean()])
        for other_index, other in enumerate(found):
            if other_index == best[1] or not _leg_sized(xs[other], ys[other], params):
                continue
            other_centre = np.array([xs[other].mean(), ys[other].mean()])
            if float(np.hypot(*(other_centre - centre))) <= params.leg_pair_max_gap_m \
                    and _seen_between(xs, ys, sensor, run, other):
                legs = 2
                px, py = np.concatenate((px, xs[other])), np.concatenate((py, ys[other]))
                break
    feats = features_of(px, py, sensor, params, legs=legs, speed_mps=speed_mps)
    return _decide(feats, params)


def _decide(feats: ShapeFeatures, params: ShapeParams) -> ShapeCue:
    """The rules 2-7 of the module docstring on the features."""
    cue = _motion_or_legs(feats, params)
    return cue if cue is not None else _outline(feats, params)


def _motion_or_legs(feats: ShapeFeatures, params: ShapeParams) -> Optional[ShapeCue]:
    """Rules 2 and 3: a moving object, two legs, one leg (None: not leg-sized, the outline decides)."""
    if feats.speed_mps is not None and feats.speed_mps >= params.moving_speed_mps:
        return ShapeCue(PERSON, 0.9, f"moves at {feats.speed_mps:.2f} m/s", feats)
    if feats.legs == 2:
        if params.two_legs_person:
            return ShapeCue(PERSON, 0.85, "two leg-sized arcs side by side", feats)
        return ShapeCue(UNSURE, 0.5, "two static leg-sized arcs side by side (a person's or furniture's legs)", feats)
    return _lone_leg(feats, params) if feats.legs == 1 else None


def _lone_leg(feats: ShapeFeatures, params: ShapeParams) -> ShapeCue:
    """Rule 3's one leg-sized arc: a person if clearly curved (and ``lone_leg_person``), else unsure."""
    curved = feats.circle_rms_m < params.curvature_ratio * feats.line_rms_m and feats.bulges
    if feats.points >= MIN_SIDE_POINTS and curved and feats.line_rms_m > feats.noise_m \
            and feats.circle_radius_m <= params.leg_max_width_m:
        if params.lone_leg_person:
            return ShapeCue(PERSON, 0.6, "one curved leg-sized arc", feats)
        return ShapeCue(UNSURE, 0.5, "one static curved leg-sized arc (a leg, a pole, a bottle)", feats)
    return ShapeCue(UNSURE, 0.5, f"a small piece of {feats.size_m:.2f} m, not clearly curved", feats)


def _outline(feats: ShapeFeatures, params: ShapeParams) -> ShapeCue:
    """Rules 4-7: too few hits, a round body, a box outline, neither."""
    if feats.points < params.min_points:
        return ShapeCue(UNSURE, 0.5, f"{feats.points} hits (fewer than {params.min_points})", feats)
    tolerance = params.straight_sigmas * feats.noise_m
    square = math.isfinite(feats.corner_rms_m) and abs(feats.corner_angle_deg - 90.0) <= RIGHT_ANGLE_TOLERANCE_DEG
    right_corner = square and feats.corner_rms_m <= tolerance
    straight = min(feats.line_rms_m, feats.corner_rms_m) if square else feats.line_rms_m  # a box's outline
    if (feats.bulges and params.body_min_radius_m <= feats.circle_radius_m <= params.body_max_radius_m
            and feats.circle_rms_m <= params.curvature_ratio * straight and feats.line_rms_m > tolerance):
        if not params.round_body_person:
            return ShapeCue(UNSURE, 0.5, f"static round body of radius {feats.circle_radius_m:.2f} m (a person, a "
                            "drum, a bin, a bag)", feats)
        ratio = feats.circle_rms_m / straight
        confidence = min(0.95, 0.6 + 0.4 * (1.0 - ratio / params.curvature_ratio))
        return ShapeCue(PERSON, confidence, f"round body of radius {feats.circle_radius_m:.2f} m", feats)
    if feats.line_rms_m <= tolerance or right_corner:
        return _box(feats, params, right_corner and feats.line_rms_m > tolerance)
    return ShapeCue(UNSURE, 0.5, "neither straight nor a body's curve", feats)


def _box(feats: ShapeFeatures, params: ShapeParams, corner: bool) -> ShapeCue:
    """Rule 6: a box outline of a box's size (``corner``: two faces at a right angle)."""
    if feats.size_m > params.box_max_size_m:
        return ShapeCue(UNSURE, 0.6, f"straight but {feats.size_m:.2f} m across: a wall or furniture", feats)
    if feats.size_m < params.box_min_size_m:
        return ShapeCue(UNSURE, 0.5, f"straight but only {feats.size_m:.2f} m across", feats)
    if corner:
        return ShapeCue(BOX, 0.9, f"corner of {feats.corner_angle_deg:.0f} deg within the noise", feats)
    if feats.points >= LONG_FACE_POINTS:
        return ShapeCue(BOX, 0.85, "straight face within the noise", feats)
    return ShapeCue(BOX, 0.7, f"straight outline of {feats.points} hits within the noise", feats)


def cue_ahead(ranges: np.ndarray, angle_min: float, angle_increment: float, range_min: float, range_max: float, *,
              reach_m: float = 1.2, half_width_m: float = 0.3, params: Optional[ShapeParams] = None,
              speed_mps: Optional[float] = None) -> ShapeCue:
    """The lidar cue of the object blocking the way ahead, from a planar scan's fields (``sensor_msgs/LaserScan``:
    ``ranges`` [m], angles [rad], range limits [m]) in a frame whose x axis points forward (the robot's): the
    object is the one with the nearest hit in the corridor ``reach_m`` [m] long and 2 x ``half_width_m`` [m] wide
    ahead of the sensor (``none`` if the corridor is empty). A scan of (nearly) 360 degrees wraps."""
    xs, ys, nearest, wrap = _ahead(ranges, angle_min, angle_increment, range_min, range_max,
                                   reach_m=reach_m, half_width_m=half_width_m)
    if nearest is None:
        return ShapeCue(NONE, 1.0, f"no hit within {reach_m:.2f} m ahead in a {2.0 * half_width_m:.2f} m wide corridor")
    return classify_shape(xs, ys, (0.0, 0.0), (float(xs[nearest]), float(ys[nearest])), params,
                          speed_mps=speed_mps, wrap=wrap)


def _ahead(ranges: np.ndarray, angle_min: float, angle_increment: float, range_min: float, range_max: float, *,
           reach_m: float, half_width_m: float) -> Tuple[np.ndarray, np.ndarray, Optional[int], bool]:
    """A scan's end points (xs, ys [m], NaN: no return) in its frame, the index of the nearest hit in the
    corridor ahead (None: empty) and whether the scan wraps (covers about 360 degrees)."""
    validation.number("lidar shape", "reach_m", reach_m, positive=True, unit="[m]")
    validation.number("lidar shape", "half_width_m", half_width_m, positive=True, unit="[m]")
    ranges = np.asarray(ranges, dtype=np.float64)
    angles = angle_min + angle_increment * np.arange(ranges.size)
    with np.errstate(invalid="ignore"):
        valid = np.isfinite(ranges) & (ranges >= range_min) & (ranges < range_max)
    r = np.where(valid, ranges, 0.0)
    xs = np.where(valid, r * np.cos(angles), np.nan)
    ys = np.where(valid, r * np.sin(angles), np.nan)
    with np.errstate(invalid="ignore"):
        ahead = valid & (xs > 0.0) & (xs <= reach_m) & (np.abs(ys) <= half_width_m)
    wrap = abs(angle_increment) * ranges.size >= 2.0 * math.pi - 1.5 * abs(angle_increment)
    if not ahead.any():
        return xs, ys, None, wrap
    return xs, ys, int(np.flatnonzero(ahead)[np.argmin(xs[ahead])]), wrap


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull (counter-clockwise, no repeated corner) of (N, 2) points, by the monotone chain."""
    pts: np.ndarray = np.unique(points, axis=0)
    if len(pts) < 3:
        return pts

    def half(ordered: np.ndarray) -> List[np.ndarray]:
        chain: List[np.ndarray] = []
        for p in ordered:
            while len(chain) >= 2 and float(np.cross(chain[-1] - chain[-2], p - chain[-2])) <= 0.0:
                chain.pop()
            chain.append(p)
        return chain

    lower, upper = half(pts), half(pts[::-1])
    hull: np.ndarray = np.array(lower[:-1] + upper[:-1])
    return hull


def footprint_ahead(ranges: np.ndarray, angle_min: float, angle_increment: float, range_min: float,
                    range_max: float, *, reach_m: float = 1.2, half_width_m: float = 0.3, depth_m: float = 0.0,
                    params: Optional[ShapeParams] = None) -> Optional[np.ndarray]:
    """The footprint (convex, counter-clockwise (N, 2) [m], the scan's frame) of the object ahead that
    :func:`cue_ahead` would classify: its hits and the same hits ``depth_m`` [m] farther along their beams (the
    lidar sees only the near side; 0: as deep as it is wide, at most ``box_max_size_m``). Its hits are the
    cluster's from the nearest hit's range on and within ``box_max_size_m`` of it (a wall the object touches is
    cut there). None if the corridor is empty or the object has fewer than 2 hits."""
    params = params if params is not None else ShapeParams()
    validation.number("lidar shape", "depth_m", depth_m, minimum=0.0, unit="[m]")
    xs, ys, nearest, wrap = _ahead(ranges, angle_min, angle_increment, range_min, range_max,
                                   reach_m=reach_m, half_width_m=half_width_m)
    if nearest is None:
        return None
    run = next(c for c in clusters(xs, ys, (0.0, 0.0), params, wrap=wrap) if nearest in c)
    # A box close to walls (S5: 0.15 m from each side of a 1 m passage) may be one cluster with them, and the
    # walls run on beside and behind the robot: only the cluster's hits from the object's near face on and within
    # box_max_size_m of its nearest hit are the object, so the footprint never reaches back to the robot.
    nx, ny = xs[nearest], ys[nearest]
    run = run[(xs[run] >= nx - params.gap_m) & (np.hypot(xs[run] - nx, ys[run] - ny) <= params.box_max_size_m)]
    if len(run) < 2:
        return None
    near = np.column_stack((xs[run], ys[run]))
    depth = depth_m if depth_m > 0.0 else min(_size(near[:, 0], near[:, 1]), params.box_max_size_m)
    unit = near / np.hypot(near[:, 0], near[:, 1])[:, None]
    hull = _hull(np.concatenate((near, near + depth * unit)))
    return hull if len(hull) >= 3 else None


# ---------------------------------------------------------------------------------------------- boxes among tracks
@dataclass(frozen=True)
class BoxOutline:
    """A cluster of a scan whose outline is a box's: the mean of its hits (x, y) [m] and half its extent [m]."""

    x: float
    y: float
    half_size_m: float


def box_outlines(xs: np.ndarray, ys: np.ndarray, sensor: Tuple[float, float], params: ShapeParams = ShapeParams(), *,
                 wrap: bool = True) -> List[BoxOutline]:
    """The clusters of a scan's end points (NaN: no return) that rules 4-7 call ``box`` (a straight outline or a
    right corner within the noise, box-sized), motion not asked: what stands there is a box whether or not it was
    just pushed."""
    xs = np.asarray(xs, dtype=np.float64)
    ys = np.asarray(ys, dtype=np.float64)
    found: List[BoxOutline] = []
    for run in clusters(xs, ys, sensor, params, wrap=wrap):
        if len(run) < params.min_points:
            continue
        feats = features_of(xs[run], ys[run], sensor, params)
        if _outline(feats, params).label == BOX:
            found.append(BoxOutline(feats.centre[0], feats.centre[1], 0.5 * feats.size_m))
    return found


def without_boxes(tracks: Sequence[Track], outlines: Sequence[BoxOutline], moving_speed_mps: float) -> List[Track]:
    """``tracks`` less those standing on a box outline: slower than ``moving_speed_mps`` [m/s] with their centre
    within half the outline's extent plus their radius of its hits' mean (same frame). A moving track stays: boxes
    stand still, and a person walking past a box is not it."""
    kept: List[Track] = []
    for track in tracks:
        on_box = track.speed < moving_speed_mps and any(
            math.hypot(track.x - box.x, track.y - box.y) <= box.half_size_m + track.radius for box in outlines)
        if not on_box:
            kept.append(track)
    return kept
