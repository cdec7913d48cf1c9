"""Average several trained obstacle classifiers into one ONNX model (same input, mean of the probabilities).

    python -m tools.perception.ensemble --members a.onnx b.onnx --out models/obstacle_classifier.onnx

Every member must be an export of :mod:`tools.perception.train` with the same input (``image``, NCHW)
and output (``probabilities``, softmax inside). The result has the same input and output names, so
the runtime (:class:`flex_nav.perception.classifier.ObstacleClassifier`) loads it unchanged; it costs
the members' time and size together. The members' YAML (input size, normalisation, classes) must
agree; the first one's is copied beside the result, with the members recorded under ``training``.
Needs the ``onnx`` package (requirements-train.txt).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, List, Sequence

import yaml

from flex_nav.perception.classifier import metadata_path_for

INPUT, OUTPUT = "image", "probabilities"
RUNTIME_KEYS = ("format", "input", "output", "classes", "roi")  # what the members' YAML must agree on


def combine(members: Sequence[Path]) -> Any:
    """One ModelProto whose ``probabilities`` is the mean of the members' ``probabilities``."""
    import onnx
    from onnx import compose, helper

    if len(members) < 2:
        raise ValueError(f"an ensemble needs at least 2 members, got {len(members)}")
    models = [onnx.load(str(m)) for m in members]
    first = models[0]
    for path, model in zip(members, models):
        inputs = [i.name for i in model.graph.input]
        outputs = [o.name for o in model.graph.output]
        if inputs != [INPUT] or outputs != [OUTPUT]:
            raise ValueError(f"{path}: inputs {inputs} and outputs {outputs}, expected [{INPUT!r}] and [{OUTPUT!r}]")
        if model.opset_import != first.opset_import:
            raise ValueError(f"{path}: opset {model.opset_import} differs from {members[0]}: {first.opset_import}")
    nodes, initializers, outs = [], [], []
    for k, model in enumerate(models):
        prefixed = compose.add_prefix(model, prefix=f"m{k}_")
        graph = prefixed.graph
        for node in graph.node:  # read the shared input instead of the member's own
            node.input[:] = [INPUT if name == f"m{k}_{INPUT}" else name for name in node.input]
        nodes.extend(graph.node)
        initializers.extend(graph.initializer)
        outs.append(f"m{k}_{OUTPUT}")
    scale = helper.make_tensor("ensemble_scale", onnx.TensorProto.FLOAT, [], [1.0 / len(models)])
    nodes.append(helper.make_node("Sum", outs, ["ensemble_sum"]))
    nodes.append(helper.make_node("Mul", ["ensemble_sum", "ensemble_scale"], [OUTPUT]))
    graph = helper.make_graph(nodes, "obstacle_classifier_ensemble", list(first.graph.input),
                              list(first.graph.output), [*initializers, scale])
    model = helper.make_model(graph, opset_imports=list(first.opset_import), producer_name="flex_nav ensemble")
    model.ir_version = first.ir_version
    onnx.checker.check_model(model)
    return model


def main(argv: List[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--members", type=Path, nargs="+", required=True, help="ONNX exports of tools.perception.train")
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args(argv)
    import onnx

    docs = [yaml.safe_load(metadata_path_for(m).read_text()) for m in args.members]
    for path, doc in zip(args.members, docs):
        for key in RUNTIME_KEYS:
            if doc.get(key) != docs[0].get(key):
                raise ValueError(f"{metadata_path_for(path)}: {key} {doc.get(key)} differs from the first member's "
                                 f"{docs[0].get(key)}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    onnx.save(combine(args.members), str(args.out))
    doc = {key: docs[0][key] for key in RUNTIME_KEYS}
    doc["model"] = args.out.name
    members = [{"model": str(m), **(d.get("training") or {})} for m, d in zip(args.members, docs)]
    doc["training"] = {"ensemble_command": "python -m tools.perception.ensemble --members "
                       + " ".join(str(m) for m in args.members) + f" --out {args.out}", "members": members}
    header = ("# flex_nav obstacle classifier: metadata of the ONNX model beside it (read by\n"
              "# flex_nav.perception.classifier; written by tools/perception/ensemble.py and evaluate.py --write).\n")
    metadata_path_for(args.out).write_text(header + yaml.safe_dump(doc, sort_keys=False, width=110))
    print(f"[ensemble] {len(args.members)} members -> {args.out} ({args.out.stat().st_size / 1024:.0f} KiB)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
