"""Obstacle classifier bench: time per frame on one thread and accuracy on fresh held-out renders.

    .venv/bin/python bench/bench_classifier.py [--frames 500] [--samples 100]

1. Speed: the whole per-frame path of the node (``sensor_msgs/Image`` bytes -> RGB and depth [m] -> ROI
   patches -> normalise -> onnxruntime (1 intra-op + 1 inter-op thread) -> label) on simulator frames of the
   classifier world, against the target of 5 ms and against the raw onnxruntime call on a prepared
   input measured in the same run (the reference). Also the YOLO decoder alone on a COCO-sized raw
   output (1, 84, 8400), for users who load their own detector (their network's time comes on top).
2. Accuracy: ``--samples`` per label of freshly rendered scenes (a seed never used for training) with
   the models seen in training and with each set of held-out models (``held_out.HELD_OUT_SETS``), against the
   95 % target.
Prints the figures, the ratios, and PASS/FAIL; the exit status is 1 on FAIL.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from flex_nav.perception.classifier import DEFAULT_MODEL, ObstacleClassifier  # noqa: E402
from flex_nav.perception.image import to_depth, to_rgb  # noqa: E402
from flex_nav.perception.labels import LABELS  # noqa: E402
from flex_nav.perception.preprocess import roi_patch  # noqa: E402
from flex_nav.perception.yolo import decode  # noqa: E402
from flex_nav_sim.readings import ImageReading  # noqa: E402
from flex_nav_sim.simulation import SensorOptions, Simulation  # noqa: E402
from flex_nav_sim.world import load_world  # noqa: E402
from tools.perception.held_out import HELD_OUT_SETS  # noqa: E402
from tools.perception.scenes import Renderer, plan  # noqa: E402

TARGET_MS = 5.0  # [ms] per frame, one thread (issue 7)
TARGET_ACCURACY = 0.95
WORLD = REPO / "test" / "data" / "perception" / "classifier_world.yaml"
BENCH_SEED = 20261121  # never used for the training data (seed 7)


def sim_images() -> list[ImageReading]:
    options = SensorOptions(odometry=False, lidar=False, bumpers=False, camera=True)
    with Simulation(load_world(WORLD), seed=0, sensors=options) as sim:
        return [r for r in sim.step() if isinstance(r, ImageReading)]


def timed(fn: Callable[[], object], repeats: int) -> list[float]:
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        out.append((time.perf_counter() - t0) * 1000.0)
    return out


def summary(ms: list[float]) -> str:
    ms = sorted(ms)
    p95 = ms[int(0.95 * (len(ms) - 1))]
    return f"median {statistics.median(ms):.3f} ms, p95 {p95:.3f} ms, mean {statistics.fmean(ms):.3f} ms"


def bench_speed(clf: ObstacleClassifier, frames: int) -> bool:
    frames_in = sim_images()
    images = [f.rgb for f in frames_in]
    buffers = [(np.ascontiguousarray(f.rgb).tobytes(), f.depth.tobytes(), f.rgb.shape[1],
                f.rgb.shape[0]) for f in frames_in]

    def classify(data: bytes, depth: bytes, w: int, h: int) -> None:
        clf.classify(to_rgb(data, w, h, "rgb8"), to_depth(depth, w, h, "32FC1") if clf.uses_depth else None)

    for buffer in buffers:  # warm up
        classify(*buffer)
    tensor = clf.input_tensor(images[0], frames_in[0].depth)
    state = {"i": 0}

    def frame() -> None:
        buffer = buffers[state["i"] % len(buffers)]
        state["i"] += 1
        classify(*buffer)

    # interleave the measured path and the reference so load changes hit both alike
    full, raw, patch = [], [], []
    for _ in range(frames // 50):
        full += timed(frame, 50)
        raw += timed(lambda: clf.session.run(None, {clf.input_name: tensor}), 50)
        patch += timed(lambda: roi_patch(images[0], clf.roi, clf.metadata.width, clf.metadata.height), 50)
    median_full, median_raw = statistics.median(full), statistics.median(raw)
    inputs = "rgb8 + 32FC1 depth" if clf.uses_depth else "rgb8"
    print(f"images: {len(images)} simulator frames {images[0].shape[1]}x{images[0].shape[0]} ({inputs}), "
          f"model {DEFAULT_MODEL.name} {DEFAULT_MODEL.stat().st_size / 1024:.0f} KiB, one thread")
    print(f"  per frame (bytes -> label)      : {summary(full)}")
    print(f"  reference: onnxruntime run only : {summary(raw)}")
    print(f"  of which colour ROI crop + resize: {summary(patch)}")
    print(f"  ratio to the raw onnxruntime call: {median_full / median_raw:.2f}x")
    print(f"  ratio to the {TARGET_MS:.0f} ms target       : {median_full / TARGET_MS:.3f}x")

    rng = np.random.default_rng(0)
    nc, anchors = 80, 8400
    out = np.zeros((1, 4 + nc, anchors), np.float32)
    out[0, :2] = rng.uniform(0, 640, (2, anchors))
    out[0, 2:4] = rng.uniform(10, 200, (2, anchors))
    out[0, 4:] = rng.uniform(0, 0.05, (nc, anchors))  # background: every anchor under the threshold
    for _ in range(15):  # 15 objects, each found by 40 neighbouring anchors with jittered boxes
        idx = rng.choice(anchors, 40, replace=False)
        centre, size = rng.uniform(50, 590, 2), rng.uniform(30, 250, 2)
        out[0, 0:2, idx] = centre + rng.normal(0, 4, (40, 2))
        out[0, 2:4, idx] = size * rng.uniform(0.9, 1.1, (40, 2))
        out[0, 4 + rng.integers(nc), idx] = rng.uniform(0.3, 0.95, 40)
    yolo = timed(lambda: decode(out, nc, "raw", conf_threshold=0.25, iou_threshold=0.45), 50)
    print(f"  YOLO raw decode (1, 84, 8400), 600 candidates of 15 objects, + NMS (decoder only): {summary(yolo)}")
    ok = median_full <= TARGET_MS
    print(f"speed: {'PASS' if ok else 'FAIL'} ({median_full:.3f} ms <= {TARGET_MS} ms)")
    return ok


def bench_accuracy(clf: ObstacleClassifier, samples: int) -> bool:
    ok = True
    for split_id, split in enumerate(("test", *HELD_OUT_SETS)):
        rng = np.random.default_rng(np.random.SeedSequence([BENCH_SEED, split_id]))
        renderer = Renderer(rng)
        correct = {label: 0 for label in LABELS}
        t0 = time.perf_counter()
        try:
            for label, model in plan(LABELS, samples, split, rng):
                sample = renderer.render(label, model)
                correct[label] += clf.classify(sample.rgb, sample.depth).label == label
        finally:
            renderer.close()
        accuracy = sum(correct.values()) / (samples * len(LABELS))
        recalls = ", ".join(f"{label} {100 * n / samples:.1f} %" for label, n in correct.items())
        what = "models seen in training" if split == "test" else f"the held-out models of {split!r}"
        print(f"accuracy, {samples * len(LABELS)} fresh renders with {what}: {100 * accuracy:.2f} % "
              f"(recall {recalls}; {time.perf_counter() - t0:.0f} s) -> "
              f"{'PASS' if accuracy >= TARGET_ACCURACY else 'FAIL'} (target {100 * TARGET_ACCURACY:.0f} %)")
        ok = ok and accuracy >= TARGET_ACCURACY
    return ok


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--frames", type=int, default=500, help="timed frames (multiple of 50)")
    parser.add_argument("--samples", type=int, default=100, help="fresh renders per label and split (0 = skip)")
    args = parser.parse_args()
    clf = ObstacleClassifier()
    ok = bench_speed(clf, max(50, args.frames))
    if args.samples > 0:
        ok = bench_accuracy(clf, args.samples) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
