"""Render the obstacle classifier's dataset with the simulator's camera; reproducible from the seed.

    python -m tools.perception.render_dataset --out build/dataset --seed 7

Writes ``train.npz``, ``val.npz``, ``test.npz`` (models seen in training, new scenes) and ``unseen.npz``
(held-out people, objects and furniture; see :mod:`tools.perception.scenes`), each with ``patches``
(N, H, W, 3) uint8 = the model input before normalisation (:func:`flex_nav.perception.preprocess.roi_patch`
with the default ROI), ``depths`` (N, H, W) uint16 [mm] = the same region of the registered depth image
(:func:`flex_nav.perception.preprocess.depth_patch`, no return or beyond ``DEPTH_RANGE`` = ``DEPTH_RANGE``),
``labels`` (indices into ``classes``), ``models``, ``profiles`` and ``distances`` [m]; plus
``sheet_<split>.png`` contact sheets of full frames with the ROI drawn. Every split is cut into chunks
with their own generator from ``SeedSequence([seed, split, chunk])``, so the output does not depend on
``--workers``.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Tuple

import cv2
import numpy as np

from flex_nav.perception.labels import LABELS
from flex_nav.perception.preprocess import depth_patch, roi_patch
from flex_nav.perception.roi import Roi

PATCH_W, PATCH_H = 64, 64  # [px] the model input size (models/obstacle_classifier.yaml)
DEPTH_RANGE = 4.0  # [m] depth patches are clipped here (a Kinect's range; farther or no return = this)
DEPTH_UNIT = 0.001  # [m] per stored depth value (uint16 millimetres)
SPLITS: Dict[str, Tuple[int, int]] = {  # split: (id in the seed, samples per label)
    "train": (0, 2000), "val": (1, 200), "test": (2, 300), "unseen": (3, 300),
    "extra": (4, 3000), "val_extra": (5, 150),  # training-only models too (tools.perception.scenes.TRAIN_ONLY)
    "extra2": (6, 600), "val_extra2": (7, 100),  # boxes in passages against look-alikes (scenes.PASSAGE)
    "extra3": (8, 2000), "val_extra3": (9, 100),  # randomised furniture and marked boxes (scenes.PROCEDURAL)
    "unseen2": (10, 300),  # a second held-out set (held_out.unseen2)
    "unseen3": (11, 300),  # a third held-out set (held_out.unseen3)
    "unseen4": (12, 300),  # a fourth held-out set (held_out.unseen4)
    "extra4": (13, 1200), "val_extra4": (14, 100),  # seated people, poles on castors, tall blocks (scenes.ASSISTIVE)
    "unseen5": (15, 300),  # a fifth held-out set (held_out.unseen5)
    "unseen6": (16, 300),  # a sixth held-out set (held_out.unseen6)
    "extra5": (17, 1200), "val_extra5": (18, 100),  # people behind or on things, plants (scenes.ENCUMBERED)
    "unseen7": (19, 300),  # a seventh held-out set (held_out.unseen7)
    "extra6": (20, 1200), "val_extra6": (21, 100),  # people down on the floor (scenes.ON_FLOOR)
    "unseen8": (22, 300),  # an eighth held-out set (held_out.unseen8)
    "unseen9": (23, 300),  # a ninth held-out set (held_out.unseen9)
    "extra7": (24, 1500), "val_extra7": (25, 100),  # procedural people, objects, structures (scenes.SAMPLED)
    "unseen10": (26, 300),  # a tenth held-out set (held_out.unseen10)
    "unseen11": (27, 300),  # an eleventh held-out set (held_out.unseen11)
    "extra8": (28, 1500), "val_extra8": (29, 100),  # more procedural draws, pushers, machines (scenes.SAMPLED2)
    "unseen12": (30, 300),  # a twelfth held-out set (held_out.unseen12)
}
CHUNK = 20  # samples per label in a chunk (one generator per chunk)
SHEET_FRAMES = 24


@dataclass(frozen=True)
class Chunk:
    """The samples of one chunk (picklable, for the worker pool)."""

    patches: np.ndarray  # uint8 (N, PATCH_H, PATCH_W, 3)
    depths: np.ndarray  # uint16 (N, PATCH_H, PATCH_W) [mm]
    labels: np.ndarray  # int64 (N,), indices into LABELS
    models: List[str]
    profiles: List[str]
    distances: np.ndarray  # float32 (N,) [m]
    frames: List[np.ndarray]  # full frames for the contact sheet (chunk 0 only)


def render_chunk(args: Tuple[int, str, int, int, int]) -> Chunk:
    """Render ``count`` samples per label of one chunk."""
    from tools.perception.scenes import Renderer, plan

    seed, split, split_id, chunk, count = args
    rng = np.random.default_rng(np.random.SeedSequence([seed, split_id, chunk]))
    jobs = plan(LABELS, count, split, rng, offset=chunk)
    renderer = Renderer(rng)
    roi = Roi()
    patches: List[np.ndarray] = []
    depths: List[np.ndarray] = []
    labels: List[int] = []
    models: List[str] = []
    profiles: List[str] = []
    distances: List[float] = []
    frames: List[np.ndarray] = []
    try:
        for label, model in jobs:
            sample = renderer.render(label, model)
            patches.append(roi_patch(sample.rgb, roi, PATCH_W, PATCH_H))
            depth = depth_patch(sample.depth, roi, PATCH_W, PATCH_H, DEPTH_RANGE)
            depths.append(np.round(depth / DEPTH_UNIT).astype(np.uint16))
            labels.append(LABELS.index(label))
            models.append(model)
            profiles.append(sample.profile)
            distances.append(sample.distance)
            if chunk == 0 and len(frames) < SHEET_FRAMES:
                frames.append(sample.rgb)
    finally:
        renderer.close()
    return Chunk(np.stack(patches), np.stack(depths), np.array(labels, dtype=np.int64), models, profiles,
                 np.array(distances, dtype=np.float32), frames)


def stored_depth_metres(depths: np.ndarray) -> np.ndarray:
    """The ``depths`` array of a split file (uint16, :data:`DEPTH_UNIT`) in metres, float32."""
    return depths.astype(np.float32) * np.float32(DEPTH_UNIT)


def contact_sheet(frames: List[np.ndarray], roi: Roi, columns: int = 6) -> np.ndarray:
    tiles = []
    for rgb in frames:
        tile = rgb.copy()
        x0, y0, x1, y1 = roi.pixels(tile.shape[1], tile.shape[0])
        cv2.rectangle(tile, (x0, y0), (x1 - 1, y1 - 1), (255, 0, 0), 1)
        tiles.append(cv2.resize(tile, (160, 120), interpolation=cv2.INTER_AREA))
    while len(tiles) % columns:
        tiles.append(np.zeros_like(tiles[0]))
    rows = [np.hstack(tiles[i : i + columns]) for i in range(0, len(tiles), columns)]
    return np.vstack(rows)


def main(argv: List[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=Path("build/dataset"))
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--workers", type=int, default=2, help="processes (the output does not depend on it)")
    parser.add_argument("--scale", type=float, default=1.0, help="multiply every split's size (e.g. 0.1 to try)")
    parser.add_argument("--splits", nargs="+", default=list(SPLITS), choices=list(SPLITS),
                        help="render only these splits (each split's content does not depend on the others)")
    args = parser.parse_args(argv)
    # The scene code is imported here, before the workers fork from this process (a pool per split, "fork" context):
    # a worker that imported it itself would render with whatever the files hold when its split starts, and an edit
    # during a run would change some splits and not others.
    from tools.perception import scenes  # noqa: F401

    args.out.mkdir(parents=True, exist_ok=True)
    summary: Dict[str, object] = {}
    started = time.monotonic()
    summary_file = args.out / "summary.json"
    if summary_file.exists() and set(args.splits) != set(SPLITS):
        summary = json.loads(summary_file.read_text())  # keep the records of the splits not rendered now
    for split in args.splits:
        split_id, per_label = SPLITS[split]
        total = max(1, round(per_label * args.scale))  # per label
        chunks = [(args.seed, split, split_id, i, min(CHUNK, total - i * CHUNK))
                  for i in range((total + CHUNK - 1) // CHUNK)]
        t0 = time.monotonic()
        if args.workers > 1:
            with ProcessPoolExecutor(max_workers=args.workers, mp_context=multiprocessing.get_context("fork")) as pool:
                parts = list(pool.map(render_chunk, chunks))
        else:
            parts = [render_chunk(c) for c in chunks]
        patches = np.concatenate([p.patches for p in parts])
        depths = np.concatenate([p.depths for p in parts])
        labels = np.concatenate([p.labels for p in parts])
        models = [m for p in parts for m in p.models]
        profiles = [m for p in parts for m in p.profiles]
        distances = np.concatenate([p.distances for p in parts])
        np.savez_compressed(args.out / f"{split}.npz", patches=patches, depths=depths, labels=labels,
                            models=np.array(models), profiles=np.array(profiles), distances=distances,
                            classes=np.array(LABELS))
        sheet = contact_sheet(parts[0].frames, Roi())
        cv2.imwrite(str(args.out / f"sheet_{split}.png"), cv2.cvtColor(sheet, cv2.COLOR_RGB2BGR))
        counts = {label: int((labels == i).sum()) for i, label in enumerate(LABELS)}
        summary[split] = {"samples": len(labels), "per_label": counts, "models": sorted(set(models)),
                          "seconds": round(time.monotonic() - t0, 1)}
        print(f"[render_dataset] {split}: {len(labels)} samples {counts} in {time.monotonic() - t0:.0f} s", flush=True)
    summary["seed"] = args.seed
    summary_file.write_text(json.dumps(summary, indent=2) + "\n")
    print(f"[render_dataset] done in {time.monotonic() - started:.0f} s -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
