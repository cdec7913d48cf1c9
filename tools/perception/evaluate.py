"""Evaluate an obstacle classifier (ONNX + its YAML) on the rendered splits: accuracy, precision, recall.

    python -m tools.perception.evaluate --model models/obstacle_classifier.onnx --data build/dataset

Runs the model exactly as the node does (:class:`flex_nav.perception.classifier.ObstacleClassifier`,
onnxruntime, one thread) on the stored ROI patches (and depth patches, for an RGB-D model) of the
``val*`` splits (model selection), ``test`` (models seen in training, new scenes) and ``unseen*`` (the
sets of people, objects and furniture held out of training), and prints per split the accuracy, per
class precision and recall, the confusion matrix and the accuracy per scene model.
``--write`` stores the figures in the model's YAML (``evaluation``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import yaml

from flex_nav.perception.classifier import FORMAT, ObstacleClassifier, metadata_path_for
from flex_nav.perception.preprocess import DepthScaling
from flex_nav.perception.roi import Roi
from tools.perception.render_dataset import SPLITS as RENDERED_SPLITS
from tools.perception.render_dataset import stored_depth_metres

SPLITS = (*(s for s in RENDERED_SPLITS if s.startswith("val")), "test",  # selection, seen, held out
          *(s for s in RENDERED_SPLITS if s.startswith("unseen")))
BATCH = 256


def metrics(truth: np.ndarray, predicted: np.ndarray, classes: Sequence[str], models: np.ndarray) -> Dict[str, Any]:
    confusion = np.zeros((len(classes), len(classes)), dtype=np.int64)  # rows: truth, columns: predicted
    np.add.at(confusion, (truth, predicted), 1)
    per_class = {}
    for i, name in enumerate(classes):
        tp = int(confusion[i, i])
        predicted_i, actual_i = int(confusion[:, i].sum()), int(confusion[i].sum())
        per_class[name] = {
            "precision": round(tp / predicted_i, 4) if predicted_i else None,
            "recall": round(tp / actual_i, 4) if actual_i else None,
            "samples": actual_i,
        }
    per_model = {str(m): round(float((predicted[models == m] == truth[models == m]).mean()), 4)
                 for m in sorted(set(models.tolist()))}
    return {
        "samples": len(truth),
        "accuracy": round(float((truth == predicted).mean()), 4),
        "per_class": per_class,
        "confusion": confusion.tolist(),
        "per_model_accuracy": per_model,
    }


def evaluate_splits(model: Path, data: Path, splits: Sequence[str] = SPLITS) -> Dict[str, Any]:
    classifier = ObstacleClassifier(model)
    classes = list(classifier.metadata.classes)
    results: Dict[str, Any] = {}
    for split in splits:
        file = data / f"{split}.npz"
        if not file.exists():
            print(f"[evaluate] {file} missing; skipped")
            continue
        with np.load(file) as f:
            patches, labels, models = f["patches"], f["labels"], f["models"]
            data_classes = [str(c) for c in f["classes"]]
            depths = stored_depth_metres(f["depths"]) if "depths" in f else None
        predicted: List[int] = []
        for i in range(0, len(patches), BATCH):
            depth = None if depths is None or not classifier.uses_depth else depths[i : i + BATCH]
            probs = classifier.probabilities(classifier.batch_tensor(patches[i : i + BATCH], depth))
            predicted.extend(data_classes.index(classifier.decide(p).label) for p in probs)
        results[split] = metrics(labels, np.array(predicted), data_classes, models)
        report(split, results[split], data_classes)
    del classes
    return results


def report(split: str, result: Dict[str, Any], classes: Sequence[str]) -> None:
    print(f"\n[evaluate] {split}: {result['samples']} samples, accuracy {100 * result['accuracy']:.2f} %")
    print(f"  {'class':<9} {'precision':>9} {'recall':>7} {'samples':>7}")
    for name in classes:
        c = result["per_class"][name]
        p = "-" if c["precision"] is None else f"{100 * c['precision']:.1f} %"
        r = "-" if c["recall"] is None else f"{100 * c['recall']:.1f} %"
        print(f"  {name:<9} {p:>9} {r:>7} {c['samples']:>7}")
    print("  confusion (rows truth, columns predicted):", result["confusion"])
    print("  accuracy per scene model:", ", ".join(f"{m} {100 * a:.0f} %"
                                                   for m, a in result["per_model_accuracy"].items()))


def write_metadata(
    model: Path,
    classes: Sequence[str],
    mean: Sequence[float],
    std: Sequence[float],
    size: Tuple[int, int],
    *,
    depth: Optional[DepthScaling] = None,
    training: Optional[Dict[str, Any]] = None,
    evaluation: Optional[Dict[str, Any]] = None,
) -> Path:
    """Write (or update) the model's YAML: what the runtime needs, then training and evaluation records."""
    path = metadata_path_for(model)
    old = yaml.safe_load(path.read_text()) if path.exists() else {}
    inp: Dict[str, Any] = {"width": size[0], "height": size[1], "mean": [float(m) for m in mean],
                           "std": [float(s) for s in std], "layout": "NCHW, RGB, pixel / 255 then (x - mean) / std"}
    if depth is not None:
        inp["depth"] = {"max_range": depth.max_range, "mean": depth.mean, "std": depth.std}
        inp["layout"] = ("NCHW, R G B D: pixel / 255 then (x - mean) / std; D = depth [m] (registered; none or "
                         "beyond max_range = max_range) / max_range then (x - depth.mean) / depth.std")
    doc = {
        "format": FORMAT,
        "model": model.name,
        "input": inp,
        "output": "probabilities",
        "classes": list(classes),
        "roi": [Roi().x_min, Roi().y_min, Roi().x_max, Roi().y_max],
        "training": training if training is not None else old.get("training"),
        "evaluation": _summary(evaluation) if evaluation is not None else old.get("evaluation"),
    }
    header = ("# flex_nav obstacle classifier: metadata of the ONNX model beside it (read by\n"
              "# flex_nav.perception.classifier; written by tools/perception/train.py and evaluate.py --write).\n")
    path.write_text(header + yaml.safe_dump(doc, sort_keys=False, width=110))
    return path


def _summary(evaluation: Dict[str, Any]) -> Dict[str, Any]:
    return {split: {"samples": r["samples"], "accuracy": r["accuracy"], "per_class": r["per_class"],
                    "confusion": r["confusion"], "per_model_accuracy": r["per_model_accuracy"]}
            for split, r in evaluation.items()}


def main(argv: List[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--model", type=Path, default=Path("models/obstacle_classifier.onnx"))
    parser.add_argument("--data", type=Path, default=Path("build/dataset"))
    parser.add_argument("--write", action="store_true", help="store the figures in the model's YAML")
    args = parser.parse_args(argv)
    results = evaluate_splits(args.model, args.data)
    if args.write:
        classifier = ObstacleClassifier(args.model)
        meta = classifier.metadata
        write_metadata(args.model, meta.classes, meta.mean, meta.std, (meta.width, meta.height), depth=meta.depth,
                       evaluation=results)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
