"""Measure the fused (camera + lidar) obstacle decision on the classifier's held-out sets (issue 28).

    python -m tools.perception.evaluate_fused --split unseen3 [--split unseen4 ..] [--json build/fused.json]

The stored splits hold only the camera's ROI patches, so every scene is built and rendered again exactly as
:func:`tools.perception.render_dataset.render_chunk` renders it (same ``SeedSequence([seed, split, chunk])``, same
:func:`tools.perception.scenes.plan`, the same :class:`tools.perception.scenes.Renderer`; the frozen builders are not
touched). The only difference: the renderer's pybullet client is wrapped by :class:`CollidingClient`, which gives
every visual-only primitive the scenes create (box, cylinder, capsule, sphere) a collision shape of the same
geometry, so rays hit what the camera sees (URDF/MJCF models bring their own collision shapes). Nothing the scene
code draws from its generator changes, so the camera frames are the stored ones: the camera-alone figures this tool
prints must equal ``tools.perception.evaluate``'s on the same split (a check of the reconstruction).

From the same robot pose as the camera (base at the origin, heading +x) the TurtleBot 4's lidar
(``sim/robots/turtlebot4.yaml``: RPLIDAR A1M8 at (-0.04, 0, 0.20) m, 360 beams of 1 degree, 0.15-12 m, range noise
0.5 mm + 0.5 % one sigma) is cast with the simulator's own :class:`flex_nav_sim.sensors.Lidar` (one
``rayTestBatch``, rays from the body outline; the noise from a generator of its own, so the scene draws are not
disturbed). Every sample uses the TurtleBot 4's lidar, whichever robot's camera rendered it. An object below the
scan plane (0.20 m) gives no return, so its lidar cue is ``none``; that is measured, not corrected.

Decided before measuring (nothing below was tuned on any split):

- camera cue: the shipped model on the frame, as ``tools.perception.evaluate`` runs it; one frame per scene, taken
  as a window of identical frames (``CameraCue(label, confidence, 1, 1, label, confidence)``: the vote and the
  latest frame are that frame). ``camera_min_votes`` is 0, so the vote count does not matter.
- lidar cue: :func:`flex_nav.perception.lidar_shape.cue_ahead` with the parameters of ``ObstacleFusionState``
  (reach 1.2 m, corridor half width 0.3 m, default :class:`~flex_nav.perception.lidar_shape.ShapeParams`), no speed
  (the scenes stand still).
- rule: :func:`flex_nav.perception.fusion.fuse` with the default :class:`~flex_nav.perception.fusion.FusionParams`
  (camera 0.7, lidar 0.6, ``max_looks`` 2), unchanged.
- ``look_again`` is scored with the looks exhausted: the scored decision is ``fuse(camera, lidar,
  looks=max_looks)``, the rule's final answer with no second view (each scene has one viewpoint; a second look
  would see nearly the same frame and scan, which is what this assumes). How often the rule would have asked to
  look again (``fuse(.., looks=0)``) is reported beside it, not scored.
- score: the fused decision against the scene's label (person / movable / clear; ``unknown`` is wrong); "people
  taken for movable" = person scenes decided ``movable`` (the unsafe error), for the camera alone and fused.

Added after the first full run had been seen (a slice, nothing tuned): the same two accuracies on the scenes whose
target is at most ``NEAR_M`` = 1.0 m from the camera (the dataset puts targets 0.5-2.5 m away; the lidar's corridor
ends 1.2 m ahead, and a blocked robot classifies from about 0.55 m), so the fusion's figure where the lidar can
see the object is not diluted by the scenes where it cannot.

Choosing a rule (second round, 2026-11-29; written down before any candidate was scored). The first run (all
defaults above) was worse than the camera alone on every held-out set: a lidar box beat the camera's clear (rule row
7: furniture with flat faces, and a seated person's chair, cart or bench, became movable) and a static lidar
``person`` (a round body, a lone leg, two leg-like arcs: drums, bins, bags, plants, chair and table legs) became a
person. The candidates (:data:`CANDIDATES`) cross six lidar ``person`` cues with three row 7s:

- P0: as before (moves; two leg-sized arcs; a lone curved leg-sized arc; a static round body);
- P1: moves, or two leg-sized arcs (a lone leg and a static round body are ``unsure``);
- P2 / P3: P1 with each leg at least 0.04 / 0.06 m across (a person's leg in these scenes is a capsule of
  0.05-0.08 m radius; a chair's or table's leg is thinner);
- P4: P0 with each leg at least 0.06 m across;
- P5: ``person`` only for a moving object (every static cue ``unsure``);
- row 7 (``FusionParams.box_beats_clear``): A: a lidar box beats any camera clear (as before); U: only an unsure
  one (below ``camera_min_confidence``); N: never (a box still asks to look again; after the looks the camera's
  clear stands).

Everything else stays as above (camera 0.7, lidar box 0.6, ``max_looks`` 2, the corridor, looks exhausted).
Criterion: on the validation splits only (:data:`VALIDATION`: every split whose name starts with ``val``), one
render with ``--dump`` and every candidate scored offline from it (``--rescore``: the lidar cue recomputed from the
dumped ranges): among the candidates that take no more people for movable than the camera alone on any
validation split, the best mean of the splits' fused accuracies (each split one vote, compared at 0.1 point);
ties: fewer looks asked (summed over the splits), then the earlier in the list (P0A, P0U, P0N, P1A, ...). The chosen
candidate becomes the defaults of ``fusion`` and ``lidar_shape``; the held-out sets are then measured once with it,
whatever they show, and no other candidate is run on them.

Chosen (``--rescore build/fused_val_dump.json`` on the dump of the nine validation splits, 3 150 scenes): P5N, a
lidar ``person`` only for a moving object and row 7 only for an undecided camera; it is now the default of
:class:`~flex_nav.perception.lidar_shape.ShapeParams` and :class:`~flex_nav.perception.fusion.FusionParams`, so this
tool without options measures it (the first run's rule is candidate P0A).

One process, one onnxruntime thread; no pool (the machine is shared).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np
import pybullet

from flex_nav.exceptions import ConfigError
from flex_nav.perception.classifier import ObstacleClassifier
from flex_nav.perception.fusion import LOOK_AGAIN, CameraCue, FusionParams, fuse
from flex_nav.perception.labels import LABELS, MOVABLE, PERSON, Prediction
from flex_nav.perception.lidar_shape import LIDAR_LABELS, ShapeCue, ShapeParams, cue_ahead
from flex_nav.perception.preprocess import depth_patch, roi_patch
from flex_nav.perception.roi import Roi
from flex_nav_sim.profiles import LidarSpec, load_profile
from flex_nav_sim.readings import Pose2D
from flex_nav_sim.sensors import Lidar
from tools.perception.evaluate import metrics
from tools.perception.render_dataset import CHUNK, DEPTH_RANGE, DEPTH_UNIT, PATCH_H, PATCH_W, SPLITS

LIDAR_PROFILE = "turtlebot4"  # whose lidar every scene is scanned with
LIDAR_STREAM = 28  # the lidar noise generator's extra seed word (issue 28), apart from the scene's draws
REACH_M = 1.2  # [m] ObstacleFusionState's defaults for cue_ahead
HALF_WIDTH_M = 0.3  # [m]
NEAR_M = 1.0  # [m] camera to target: the scenes also scored apart (the corridor reaches 1.2 m from the lidar)
HELD_OUT = tuple(s for s in SPLITS if s.startswith("unseen"))
VALIDATION = tuple(s for s in SPLITS if s.startswith("val"))


@dataclass(frozen=True)
class Candidate:
    """A candidate rule: the lidar cue's parameters and the fusion's (see "Choosing a rule" in the module
    docstring); every switched field is given explicitly, so a candidate does not change with the defaults."""

    name: str
    what: str
    shape: ShapeParams
    fusion: FusionParams


def _candidates() -> Tuple[Candidate, ...]:
    lidar = {  # name: (what, the lidar person switches and the least leg width [m])
        "P0": ("lidar person as before: moves, two legs, a lone curved leg, a round body", (True, True, True, 0.0)),
        "P1": ("lidar person: moves or two legs (a lone leg, a static round body: unsure)", (True, False, False, 0.0)),
        "P2": ("P1, each leg at least 0.04 m across", (True, False, False, 0.04)),
        "P3": ("P1, each leg at least 0.06 m across", (True, False, False, 0.06)),
        "P4": ("P0, each leg at least 0.06 m across", (True, True, True, 0.06)),
        "P5": ("lidar person only for a moving object (static: unsure)", (False, False, False, 0.0)),
    }
    rows = {"A": "always", "U": "unsure", "N": "never"}
    out = []
    for lname, (what, (two, lone, body, width)) in lidar.items():
        shape = ShapeParams(two_legs_person=two, lone_leg_person=lone, round_body_person=body, leg_min_width_m=width)
        for rname, mode in rows.items():
            out.append(Candidate(f"{lname}{rname}", f"{what}; row 7: a lidar box beats {mode} a camera clear"
                                 if mode != "unsure" else f"{what}; row 7: a lidar box beats an unsure camera clear",
                                 shape, FusionParams(box_beats_clear=mode)))
    return tuple(out)


CANDIDATES: Tuple[Candidate, ...] = _candidates()


class CollidingClient:
    """A pybullet client whose visual-only bodies also collide: :meth:`createVisualShape` remembers each primitive's
    geometry, :meth:`createMultiBody` without a collision shape adds one of the same geometry (so ``rayTest`` hits
    it); everything else is the wrapped client's."""

    def __init__(self, client: Any) -> None:
        self._client = client
        self._geometry: Dict[int, Tuple[int, Dict[str, Any]]] = {}  # visual id: (shape type, its size keywords)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._client, name)

    def resetSimulation(self, *args: Any, **kwargs: Any) -> Any:  # noqa: N802 (pybullet's name)
        self._geometry.clear()
        return self._client.resetSimulation(*args, **kwargs)

    def createVisualShape(self, shapeType: int, **kwargs: Any) -> int:  # noqa: N802,N803 (pybullet's names)
        visual = int(self._client.createVisualShape(shapeType, **kwargs))
        size: Dict[str, Any] = {key: kwargs[key] for key in ("halfExtents", "radius", "length") if key in kwargs}
        self._geometry[visual] = (shapeType, size)
        return visual

    def createMultiBody(self, *args: Any, **kwargs: Any) -> int:  # noqa: N802 (pybullet's name)
        """pybullet's ``createMultiBody(baseMass, baseCollisionShapeIndex, baseVisualShapeIndex, ...)``, positional
        or by keyword; a remembered visual primitive without a collision shape gets one of its geometry."""
        names = ("baseMass", "baseCollisionShapeIndex", "baseVisualShapeIndex")
        given = dict(zip(names, args))
        given.update({key: kwargs[key] for key in names if key in kwargs})
        visual = int(given.get("baseVisualShapeIndex", -1))
        if int(given.get("baseCollisionShapeIndex", -1)) < 0 and visual in self._geometry:
            collision = self.collision_for(*self._geometry[visual])
            if len(args) > 1:
                args = (args[0], collision, *args[2:])
            else:
                kwargs["baseCollisionShapeIndex"] = collision
        return int(self._client.createMultiBody(*args, **kwargs))

    def collision_for(self, shape: int, size: Dict[str, Any]) -> int:
        """A collision shape of a visual primitive's geometry (a visual's ``length`` is a collision's ``height``)."""
        if shape == pybullet.GEOM_BOX:
            return int(self._client.createCollisionShape(shape, halfExtents=size["halfExtents"]))
        if shape == pybullet.GEOM_SPHERE:
            return int(self._client.createCollisionShape(shape, radius=size["radius"]))
        if shape in (pybullet.GEOM_CYLINDER, pybullet.GEOM_CAPSULE):
            return int(self._client.createCollisionShape(shape, radius=size["radius"], height=size["length"]))
        raise ConfigError(f"CollidingClient: visual shape type {shape} has no collision twin (box, sphere, cylinder, "
                          "capsule)")


def lidar_spec() -> Tuple[LidarSpec, float]:
    """The lidar every scene is scanned with and the robot's body radius [m] (rays start outside it)."""
    profile = load_profile(LIDAR_PROFILE)
    return profile.lidar, profile.base.radius


def scan_scene(lidar: Lidar, params: Optional[ShapeParams] = None) -> Tuple[np.ndarray, ShapeCue]:
    """The lidar's ranges [m] (inf: no return) for the robot at the origin heading +x, cast on the client the
    lidar was made with, and its cue of the object ahead (as ``ObstacleFusionState`` reads it)."""
    spec = lidar.spec
    ranges = lidar.scan(Pose2D(0.0, 0.0, 0.0))
    cue = cue_ahead(ranges, spec.angle_min, spec.angle_increment, spec.range_min, spec.range_max,
                    reach_m=REACH_M, half_width_m=HALF_WIDTH_M, params=params)
    return ranges, cue


def camera_cue(prediction: Prediction) -> CameraCue:
    """One frame's prediction as the camera's cue (a window of that frame)."""
    return CameraCue(prediction.label, float(prediction.confidence), 1, 1, prediction.label,
                     float(prediction.confidence))


def fused_labels(camera: CameraCue, lidar: ShapeCue, params: FusionParams) -> Tuple[str, bool]:
    """(the rule's final decision with the looks exhausted, whether it would first have asked to look again)."""
    final = fuse(camera, lidar, params.max_looks, params).label
    if final == LOOK_AGAIN:  # the rule never asks again with no looks left; guard the scoring against a change
        raise ConfigError(f"fusion asked to look again with {params.max_looks} of {params.max_looks} looks taken")
    return final, fuse(camera, lidar, 0, params).label == LOOK_AGAIN


@dataclass
class Records:
    """Per scene of a split: truth, camera's, fused and lidar labels, scene model, look-again flag."""

    truth: List[str] = field(default_factory=list)
    camera: List[str] = field(default_factory=list)
    fused: List[str] = field(default_factory=list)
    lidar: List[str] = field(default_factory=list)
    models: List[str] = field(default_factory=list)
    asked_again: List[bool] = field(default_factory=list)
    distances_m: List[float] = field(default_factory=list)  # [m] camera to target centre (0: an empty scene)

    def add(self, truth: str, camera: str, fused: str, lidar: str, *, model: str, asked_again: bool,
            distance_m: float = 0.0) -> None:
        for name, value, allowed in (("truth", truth, LABELS), ("camera", camera, LABELS), ("fused", fused, LABELS),
                                     ("lidar", lidar, LIDAR_LABELS)):
            if value not in allowed:
                raise ConfigError(f"{name} label {value!r} is not one of {allowed}")
        self.truth.append(truth)
        self.camera.append(camera)
        self.fused.append(fused)
        self.lidar.append(lidar)
        self.models.append(model)
        self.asked_again.append(asked_again)
        self.distances_m.append(float(distance_m))


def score(records: Records, near_m: float = NEAR_M) -> Dict[str, Any]:
    """Camera-alone and fused figures of a split (``tools.perception.evaluate.metrics`` each), people taken for
    movable by each, the same two accuracies on the scenes whose target is at most ``near_m`` [m] from the camera
    (``near``: where the lidar's corridor reaches; empty scenes left out), the lidar cue's labels per true class and
    how often the rule would have looked again, and per scene model the fused decisions and lidar cues."""
    if not records.truth:
        raise ConfigError("no scenes to score")
    truth = np.array([LABELS.index(t) for t in records.truth])
    models = np.array(records.models)
    distances = np.array(records.distances_m)
    near = (distances > 0.0) & (distances <= near_m)
    out: Dict[str, Any] = {"near": {"max_distance_m": near_m, "samples": int(near.sum())}}
    for name, labels in (("camera", records.camera), ("fused", records.fused)):
        predicted = np.array([LABELS.index(p) for p in labels])
        result = metrics(truth, predicted, LABELS, models)
        unsafe = (truth == LABELS.index(PERSON)) & (predicted == LABELS.index(MOVABLE))
        result["person_as_movable"] = int(np.sum(unsafe))
        out[name] = result
        out["near"][name] = round(float((predicted[near] == truth[near]).mean()), 4) if near.any() else None
        out["near"][f"{name}_person_as_movable"] = int(np.sum(unsafe & near))
    pairs = list(zip(records.truth, records.lidar))
    out["lidar_by_truth"] = {label: {cue: pairs.count((label, cue)) for cue in LIDAR_LABELS} for label in LABELS}
    out["asked_again"] = int(sum(records.asked_again))
    out["per_model"] = {model: {"fused": {label: 0 for label in LABELS}, "lidar": {cue: 0 for cue in LIDAR_LABELS}}
                        for model in sorted(set(records.models))}
    for model, fused, cue in zip(records.models, records.fused, records.lidar):
        out["per_model"][model]["fused"][fused] += 1
        out["per_model"][model]["lidar"][cue] += 1
    return out


def evaluate_split(split: str, seed: int, classifier: ObstacleClassifier, *, scale: float = 1.0,
                   fusion: Optional[FusionParams] = None, shape: Optional[ShapeParams] = None,
                   dump: Optional[List[Dict[str, Any]]] = None) -> Records:
    """Render a split's scenes again (as render_dataset does), scan each with the lidar, classify and fuse;
    ``dump``: a list to which every scene's record (:func:`scene_record`) is appended."""
    from tools.perception.scenes import Renderer, plan

    if split not in SPLITS:
        raise ConfigError(f"split {split!r} is not one of {list(SPLITS)}")
    fusion = fusion if fusion is not None else FusionParams()
    split_id, per_label = SPLITS[split]
    total = max(1, round(per_label * scale))
    spec, body_radius = lidar_spec()
    roi = Roi()
    records = Records()
    for chunk in range((total + CHUNK - 1) // CHUNK):
        count = min(CHUNK, total - chunk * CHUNK)
        rng = np.random.default_rng(np.random.SeedSequence([seed, split_id, chunk]))
        jobs = plan(LABELS, count, split, rng, offset=chunk)
        renderer = Renderer(rng)
        renderer.client = CollidingClient(renderer.client)
        lidar = Lidar(renderer.client, spec, body_radius,
                      np.random.default_rng(np.random.SeedSequence([seed, split_id, chunk, LIDAR_STREAM])))
        patches, depths, cues, distances, scans = [], [], [], [], []
        try:
            for label, model in jobs:
                sample = renderer.render(label, model)
                patches.append(roi_patch(sample.rgb, roi, PATCH_W, PATCH_H))
                stored = np.round(depth_patch(sample.depth, roi, PATCH_W, PATCH_H, DEPTH_RANGE) / DEPTH_UNIT)
                depths.append(stored.astype(np.uint16).astype(np.float32) * np.float32(DEPTH_UNIT))
                ranges, cue = scan_scene(lidar, shape)
                cues.append(cue)
                scans.append(ranges)
                distances.append(sample.distance)
        finally:
            renderer.close()
        depth = np.stack(depths) if classifier.uses_depth else None
        probs = classifier.probabilities(classifier.batch_tensor(np.stack(patches), depth))
        for (label, model), p, cue, distance, ranges in zip(jobs, probs, cues, distances, scans):
            prediction = classifier.decide(p)
            fused, asked = fused_labels(camera_cue(prediction), cue, fusion)
            if dump is not None:
                dump.append(scene_record(split, len(records.truth), truth=label, model=model,
                                         distance_m=float(distance), prediction=prediction, cue=cue, ranges=ranges))
            records.add(label, prediction.label, fused, cue.label, model=model, asked_again=asked,
                        distance_m=distance)
    return records


def scene_record(split: str, index: int, *, truth: str, model: str, distance_m: float, prediction: Prediction,
                 cue: ShapeCue, ranges: np.ndarray) -> Dict[str, Any]:
    """One scene for the dump: truth, split, scene model, distance [m], the camera's label, confidence and scores,
    the lidar cue's label, confidence, reason and features, and the scan's ranges [m] (None: no return), from which
    :func:`cue_ahead` recomputes the cue with other :class:`ShapeParams` (:func:`rescore`)."""
    features = None if cue.features is None else {
        key: (None if isinstance(value, float) and not np.isfinite(value) else value)
        for key, value in asdict(cue.features).items()}
    return {"split": split, "index": index, "truth": truth, "model": model, "distance_m": round(distance_m, 4),
            "camera": {"label": prediction.label, "confidence": float(prediction.confidence),
                       "scores": {k: float(v) for k, v in prediction.scores.items()}},
            "lidar": {"label": cue.label, "confidence": float(cue.confidence), "reason": cue.reason,
                      "features": features},
            "ranges_m": [float(r) if np.isfinite(r) else None for r in np.asarray(ranges, dtype=np.float64)]}


# ------------------------------------------------------------------------------------- offline rescoring
def dump_header(shape: ShapeParams, fusion: FusionParams) -> Dict[str, Any]:
    """What :func:`rescore` needs besides the scenes: the lidar's beam geometry, the corridor, the parameters the
    dumped cues were taken with."""
    spec, _ = lidar_spec()
    return {"lidar": {"angle_min": spec.angle_min, "angle_increment": spec.angle_increment,
                      "range_min": spec.range_min, "range_max": spec.range_max},
            "reach_m": REACH_M, "half_width_m": HALF_WIDTH_M, "shape_params": asdict(shape),
            "fusion_params": asdict(fusion)}


def dumped_ranges(scene: Mapping[str, Any]) -> np.ndarray:
    """A dumped scene's ranges [m] (inf: no return)."""
    return np.array([np.inf if r is None else r for r in scene["ranges_m"]], dtype=np.float64)


def dumped_cue(scene: Mapping[str, Any], header: Mapping[str, Any], shape: ShapeParams) -> ShapeCue:
    """The lidar cue of a dumped scene recomputed with ``shape``."""
    lidar = header["lidar"]
    return cue_ahead(dumped_ranges(scene), lidar["angle_min"], lidar["angle_increment"], lidar["range_min"],
                     lidar["range_max"], reach_m=header["reach_m"], half_width_m=header["half_width_m"], params=shape)


def rescore(dump: Mapping[str, Any], candidates: Sequence[Candidate]) -> Dict[str, Dict[str, Dict[str, Any]]]:
    """Per candidate and split of a dump (``--dump``): :func:`score` of the candidate's fused decisions (the camera
    alone is the same in each), the lidar cue recomputed from the ranges, no scene rendered again."""
    header, scenes = dump["header"], dump["scenes"]
    cues: Dict[ShapeParams, List[ShapeCue]] = {}
    out: Dict[str, Dict[str, Dict[str, Any]]] = {}
    for candidate in candidates:
        if candidate.shape not in cues:
            cues[candidate.shape] = [dumped_cue(scene, header, candidate.shape) for scene in scenes]
        per_split: Dict[str, Records] = {}
        for scene, cue in zip(scenes, cues[candidate.shape]):
            cam = scene["camera"]
            camera = CameraCue(cam["label"], cam["confidence"], 1, 1, cam["label"], cam["confidence"])
            fused, asked = fused_labels(camera, cue, candidate.fusion)
            per_split.setdefault(scene["split"], Records()).add(
                scene["truth"], cam["label"], fused, cue.label, model=scene["model"], asked_again=asked,
                distance_m=scene["distance_m"])
        out[candidate.name] = {split: score(records) for split, records in per_split.items()}
    return out


def summary(per_split: Mapping[str, Mapping[str, Any]]) -> Dict[str, Any]:
    """Over a candidate's splits: the mean of the splits' accuracies (each split one vote), camera alone and
    fused; people taken for movable, summed; splits where fused took more people for movable than the camera
    alone; looks asked, summed."""
    splits = sorted(per_split)
    return {
        "camera_mean": float(np.mean([per_split[s]["camera"]["accuracy"] for s in splits])),
        "fused_mean": float(np.mean([per_split[s]["fused"]["accuracy"] for s in splits])),
        "camera_person_as_movable": sum(per_split[s]["camera"]["person_as_movable"] for s in splits),
        "fused_person_as_movable": sum(per_split[s]["fused"]["person_as_movable"] for s in splits),
        "less_safe_splits": [s for s in splits if per_split[s]["fused"]["person_as_movable"]
                             > per_split[s]["camera"]["person_as_movable"]],
        "asked_again": sum(per_split[s]["asked_again"] for s in splits),
    }


def choose(results: Mapping[str, Mapping[str, Mapping[str, Any]]], order: Sequence[str]) -> Optional[str]:
    """The criterion stated in the module docstring, on per-candidate per-split results (:func:`rescore`):
    among the candidates with no split where fused took more people for movable than the camera alone, the
    best mean accuracy at 0.1-point resolution; ties: fewer looks asked, then the earlier in ``order``. None if
    no candidate is eligible."""
    eligible = [name for name in order if not summary(results[name])["less_safe_splits"]]
    if not eligible:
        return None

    def key(name: str) -> Tuple[float, int, int]:
        s = summary(results[name])
        return (-round(100.0 * s["fused_mean"], 1), s["asked_again"], list(order).index(name))

    return min(eligible, key=key)


def report_candidates(results: Mapping[str, Mapping[str, Mapping[str, Any]]],
                      candidates: Sequence[Candidate]) -> Optional[str]:
    """Print one line per candidate and the chosen one; returns its name."""
    for candidate in candidates:
        s = summary(results[candidate.name])
        print(f"{candidate.name}: mean accuracy camera {100 * s['camera_mean']:.1f} %, fused "
              f"{100 * s['fused_mean']:.1f} %; people taken for movable {s['camera_person_as_movable']} -> "
              f"{s['fused_person_as_movable']} (less safe on {s['less_safe_splits'] or 'no split'}); looks asked "
              f"{s['asked_again']} | {candidate.what}", flush=True)
    chosen = choose(results, [c.name for c in candidates])
    print(f"chosen by the stated criterion: {chosen}", flush=True)
    return chosen


def report(split: str, result: Dict[str, Any], seconds: float) -> None:
    cam, fus = result["camera"], result["fused"]
    print(f"\n[evaluate_fused] {split}: {cam['samples']} scenes in {seconds:.0f} s: camera alone "
          f"{100 * cam['accuracy']:.1f} %, fused {100 * fus['accuracy']:.1f} %; people taken for movable "
          f"{cam['person_as_movable']} -> {fus['person_as_movable']}; the rule would look again on "
          f"{result['asked_again']}", flush=True)
    near = result["near"]
    print(f"  within {near['max_distance_m']:g} m of the camera ({near['samples']} scenes): camera "
          f"{100 * (near['camera'] or 0.0):.1f} %, fused {100 * (near['fused'] or 0.0):.1f} %; people taken for "
          f"movable {near['camera_person_as_movable']} -> {near['fused_person_as_movable']}", flush=True)
    for name in ("camera", "fused"):
        recall = ", ".join(f"{label} {100 * (result[name]['per_class'][label]['recall'] or 0.0):.1f} %"
                           for label in LABELS)
        print(f"  {name}: recall {recall}; confusion {result[name]['confusion']}")
    print("  lidar cue by true class:", result["lidar_by_truth"])
    worst = sorted(fus["per_model_accuracy"].items(), key=lambda kv: kv[1])
    print("  fused per model (camera):", ", ".join(f"{m} {100 * a:.0f} % ({100 * cam['per_model_accuracy'][m]:.0f} %)"
                                                   for m, a in worst), flush=True)


def main(argv: Sequence[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--model", type=Path, default=Path("models/obstacle_classifier.onnx"))
    parser.add_argument("--split", action="append", choices=list(SPLITS),
                        help="a split to measure (repeat; default: every held-out set, in order)")
    parser.add_argument("--seed", type=int, default=7, help="the dataset's seed (render_dataset --seed)")
    parser.add_argument("--scale", type=float, default=1.0, help="fraction of each split (e.g. 0.1 to try)")
    parser.add_argument("--json", type=Path, help="write the figures here (updated after every split)")
    parser.add_argument("--dump", type=Path, help="write every scene's record here (JSON, updated after every "
                        "split): truth, split, model, both cues, the lidar's features and ranges")
    parser.add_argument("--rescore", type=Path, help="render nothing: score the candidate rules (CANDIDATES) on "
                        "this dump's scenes and name the one the stated criterion chooses")
    args = parser.parse_args(argv)
    if args.rescore is not None:
        return _rescore_main(args.rescore, args.json)
    if not 0.0 < args.scale <= 1.0:
        raise ConfigError(f"--scale must be in (0, 1], got {args.scale}")
    classifier = ObstacleClassifier(args.model)
    shape, fusion = ShapeParams(), FusionParams()
    dump: Dict[str, Any] = {"header": dump_header(shape, fusion), "scenes": []}
    results: Dict[str, Any] = {}
    for split in args.split or HELD_OUT:
        started = time.monotonic()
        result = score(evaluate_split(split, args.seed, classifier, scale=args.scale, fusion=fusion, shape=shape,
                                      dump=dump["scenes"] if args.dump is not None else None))
        result["seconds"] = round(time.monotonic() - started, 1)
        result["load_1min"] = round(_load(), 2)
        results[split] = result
        report(split, result, result["seconds"])
        for path, content in ((args.json, results), (args.dump, dump)):
            if path is not None:
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(json.dumps(content, indent=None if content is dump else 1) + "\n")
    return 0


def _rescore_main(path: Path, json_out: Optional[Path]) -> int:
    dump = json.loads(path.read_text())
    header, scenes = dump["header"], dump["scenes"]
    splits = sorted({scene["split"] for scene in scenes})
    print(f"[evaluate_fused] {len(scenes)} dumped scenes of {splits}", flush=True)
    shape = ShapeParams(**header["shape_params"])
    differ = sum(dumped_cue(scene, header, shape).label != scene["lidar"]["label"] for scene in scenes)
    print(f"check: the lidar cue recomputed from the dumped ranges with the dump's parameters differs on {differ} "
          f"of {len(scenes)} scenes", flush=True)
    started = time.monotonic()
    results = rescore(dump, CANDIDATES)
    print(f"{len(CANDIDATES)} candidates scored in {time.monotonic() - started:.1f} s", flush=True)
    chosen = report_candidates(results, CANDIDATES)
    if json_out is not None:
        json_out.parent.mkdir(parents=True, exist_ok=True)
        json_out.write_text(json.dumps({"chosen": chosen, "summary": {name: summary(r) for name, r in results.items()},
                                        "per_split": results}, indent=1) + "\n")
    return 0


def _load() -> float:
    import os

    return os.getloadavg()[0]


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
