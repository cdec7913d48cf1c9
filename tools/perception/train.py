"""Train the obstacle classifier (a small CNN) on the rendered dataset and export the shipped ONNX model.

    pip install -r requirements-train.txt      # torch, CPU, training only
    python -m tools.perception.render_dataset --out build/dataset --seed 7
    python -m tools.perception.train --data build/dataset --seed 7 --out models/obstacle_classifier.onnx

Trains on :data:`TRAIN_SPLITS` (``train`` and ``extra`` .. ``extra8``: the training-only models of
:data:`tools.perception.scenes.TRAIN_ONLY`, boxes in passages (twice), randomised furniture, seated people, people
behind or on things, people on the floor, two rounds of procedural people, objects and structures; see
:func:`tools.perception.scenes.models_for`) and selects on the ``val*``
splits: never on ``test`` or the ``unseen*`` splits. ``--input rgbd`` (the default) adds the registered depth patch as a
fourth channel (depth / ``DEPTH_RANGE``, with sensor-like noise, holes and a minimum range as
augmentation); ``--input rgb`` trains a colour-only model. Fixed seed,
CPU, ``--threads`` torch threads (1 by default; the result depends on it). The
model is picked at the epoch with the best validation accuracy, exported with
``torch.onnx.export(..., dynamo=False)`` (softmax inside the graph, dynamic batch), then evaluated
with onnxruntime on every split (:mod:`tools.perception.evaluate`); the metadata file beside the
model (``obstacle_classifier.yaml``) records input size, normalisation, classes, commands, seed and
results.
"""

from __future__ import annotations

import argparse
import json
import shlex
import sys
import time
from pathlib import Path
from typing import Any, Dict, List, Sequence, Tuple

import numpy as np

MEAN = (0.5, 0.5, 0.5)
STD = (0.25, 0.25, 0.25)
DEPTH_MEAN, DEPTH_STD = 0.5, 0.25  # on depth / DEPTH_RANGE
INPUTS = ("rgbd", "rgb")
AUGMENTATIONS = ("basic", "strong")
DATASET_COMMAND = "python -m tools.perception.render_dataset --out build/dataset --seed {seed}"
# the shipped model's recipe: ``extra2`` (boxes in passages, S4/S5's case) twice, so it weighs double
TRAIN_SPLITS = ("train", "extra", "extra2", "extra2", "extra3", "extra4", "extra5", "extra6", "extra7", "extra8")
VAL_SPLITS = ("val", "val_extra", "val_extra2", "val_extra3", "val_extra4", "val_extra5", "val_extra6",
              "val_extra7", "val_extra8")
TRAIN_COMMAND = "python -m tools.perception.train"
ALWAYS_RECORDED = ("data", "seed", "epochs", "out")  # in the recorded command even at their defaults


WIDTHS = (16, 32, 64, 96, 128)  # output channels of the conv blocks


def build_model(classes: int, widths: Sequence[int] = WIDTHS, channels: int = 4) -> Any:
    """conv3x3 blocks (``widths``) with batch norm and 2x2 max pooling after every block but the last,
    global average pooling, dropout, linear. Five blocks on 64 px: the last one sees the whole patch at
    4 x 4, so the shape of the whole object (long and raised furniture against a box) counts."""
    from torch import nn

    def block(cin: int, cout: int, pool: bool) -> List[Any]:
        layers: List[Any] = [nn.Conv2d(cin, cout, 3, padding=1, bias=False), nn.BatchNorm2d(cout), nn.ReLU()]
        return [*layers, nn.MaxPool2d(2)] if pool else layers

    layers: List[Any] = []
    for i, (cin, cout) in enumerate(zip((channels, *widths[:-1]), widths)):
        layers += block(cin, cout, i < len(widths) - 1)
    return nn.Sequential(*layers, nn.AdaptiveAvgPool2d(1), nn.Flatten(), nn.Dropout(0.2),
                         nn.Linear(widths[-1], classes))


def augment(batch: Any, gen: Any, strong: bool = False) -> Any:
    """Flips and shifts of up to 4 px (every channel), with ``strong`` :func:`augment_zoom` and
    :func:`augment_occlusion` too, then :func:`augment_colour` on the first three channels and
    :func:`augment_depth` on the fourth if there is one (on 0..1 images)."""
    import torch

    n = batch.shape[0]
    flip = torch.rand(n, generator=gen) < 0.5
    batch = torch.where(flip[:, None, None, None], batch.flip(3), batch)
    padded = torch.nn.functional.pad(batch, (4, 4, 4, 4), mode="replicate")
    dx, dy = torch.randint(0, 9, (2,), generator=gen).tolist()
    batch = padded[:, :, dy : dy + batch.shape[2], dx : dx + batch.shape[3]]
    if strong:
        batch = augment_occlusion(augment_zoom(batch, gen), gen)
    if batch.shape[1] == 3:
        return augment_colour(batch, gen)
    return torch.cat([augment_colour(batch[:, :3], gen), augment_depth(batch[:, 3:], gen)], dim=1)


def augment_zoom(batch: Any, gen: Any, max_zoom: float = 0.15) -> Any:
    """Each image scaled about its centre by 1 +- ``max_zoom`` (bilinear colour, nearest depth, edges
    replicated), as if the camera were nearer or farther: a depth channel (the fourth) is divided by the same
    factor, except lost returns (1.0), so size and depth stay consistent."""
    import torch
    from torch.nn import functional

    n = batch.shape[0]
    zoom = 1.0 + max_zoom * (2.0 * torch.rand(n, generator=gen) - 1.0)
    theta = torch.zeros(n, 2, 3)
    theta[:, 0, 0] = theta[:, 1, 1] = 1.0 / zoom
    grid = functional.affine_grid(theta, list(batch.shape), align_corners=False)
    colour = functional.grid_sample(batch[:, :3], grid, mode="bilinear", padding_mode="border", align_corners=False)
    if batch.shape[1] == 3:
        return colour
    depth = functional.grid_sample(batch[:, 3:], grid, mode="nearest", padding_mode="border", align_corners=False)
    depth = torch.where(depth >= 0.999, depth, (depth / zoom[:, None, None, None]).clamp(0.0, 1.0))
    return torch.cat([colour, depth], dim=1)


def augment_occlusion(batch: Any, gen: Any, probability: float = 0.5) -> Any:
    """In a ``probability`` share of the images, one rectangle of 6-22 px sides at a random place is painted
    over with one random colour and, on a depth channel, one random depth: a thing partly in the way."""
    import torch

    n, channels, height, width = batch.shape
    sides = torch.randint(6, 23, (n, 2), generator=gen)
    corner_y = (torch.rand(n, generator=gen) * (height - sides[:, 0] + 1)).long()
    corner_x = (torch.rand(n, generator=gen) * (width - sides[:, 1] + 1)).long()
    rows, cols = torch.arange(height)[None, :], torch.arange(width)[None, :]
    inside_y = (rows >= corner_y[:, None]) & (rows < (corner_y + sides[:, 0])[:, None])
    inside_x = (cols >= corner_x[:, None]) & (cols < (corner_x + sides[:, 1])[:, None])
    chosen = torch.rand(n, generator=gen) < probability
    mask = (inside_y[:, :, None] & inside_x[:, None, :] & chosen[:, None, None])[:, None]
    fill = torch.rand(n, channels, 1, 1, generator=gen)
    return torch.where(mask, fill.expand_as(batch), batch)


def augment_depth(depth: Any, gen: Any) -> Any:
    """Depth (N, 1, H, W) as depth / DEPTH_RANGE: a scale error of up to 3 %, noise growing with the square of
    the distance (about 1 cm at 1 m, as stereo and structured light), and in some frames what real depth
    cameras lose: returns closer than a minimum range (0.3-0.6 m) and scattered holes; lost returns read as
    the range limit (1.0), as :func:`flex_nav.perception.preprocess.depth_patch` maps them."""
    import torch

    from tools.perception.render_dataset import DEPTH_RANGE

    n = depth.shape[0]
    far = depth >= 0.999
    scale = 1.0 + 0.06 * torch.rand(n, 1, 1, 1, generator=gen) - 0.03
    metres = depth * DEPTH_RANGE * scale
    metres = metres + (0.002 + 0.01 * metres * metres) * torch.randn(depth.shape, generator=gen)
    lost = far | (metres <= 0.0)
    min_range = 0.3 + 0.3 * torch.rand(n, 1, 1, 1, generator=gen)
    clipped = torch.rand(n, 1, 1, 1, generator=gen) < 0.3
    lost |= clipped & (metres < min_range)
    holes = torch.rand(n, 1, 1, 1, generator=gen) < 0.3
    lost |= holes & (torch.rand(depth.shape, generator=gen) < 0.1 * torch.rand(n, 1, 1, 1, generator=gen))
    return torch.where(lost, torch.ones_like(depth), (metres / DEPTH_RANGE).clamp(0.0, 1.0))


def augment_colour(batch: Any, gen: Any) -> Any:
    """Brightness/contrast/colour jitter and sensor noise on RGB (N, 3, H, W) in 0..1."""
    import torch

    n = batch.shape[0]
    contrast = 0.75 + 0.5 * torch.rand(n, 1, 1, 1, generator=gen)
    brightness = 0.16 * torch.rand(n, 1, 1, 1, generator=gen) - 0.08
    tint = 1.0 + 0.1 * torch.rand(n, 3, 1, 1, generator=gen) - 0.05
    mean = batch.mean(dim=(1, 2, 3), keepdim=True)
    batch = (batch - mean) * contrast + mean + brightness
    batch = batch * tint + 0.02 * torch.rand(1, generator=gen) * torch.randn(batch.shape, generator=gen)
    return batch.clamp(0.0, 1.0)


def load_split(data: Path, split: str, depth: bool) -> Tuple[np.ndarray, np.ndarray, np.ndarray, List[str]]:
    """(N, H, W, 3 or 4) float32 images in 0..1 (depth: / DEPTH_RANGE), labels, models, classes."""
    from tools.perception.render_dataset import DEPTH_RANGE, stored_depth_metres

    with np.load(data / f"{split}.npz") as f:
        images = f["patches"].astype(np.float32) / np.float32(255.0)
        if depth:
            if "depths" not in f:
                raise ValueError(f"split {split!r} in {data} has no depth patches: render it again")
            metres = stored_depth_metres(f["depths"])
            images = np.concatenate([images, (metres / np.float32(DEPTH_RANGE))[..., None]], axis=3)
        return images, f["labels"], f["models"], [str(c) for c in f["classes"]]


def load_splits(data: Path, splits: Sequence[str], depth: bool) -> Tuple[np.ndarray, np.ndarray, List[str]]:
    """The images and labels of several splits, concatenated; ValueError if their classes differ."""
    parts = [load_split(data, split, depth) for split in splits]
    classes = parts[0][3]
    for split, part in zip(splits, parts):
        if part[3] != classes:
            raise ValueError(f"split {split!r} has classes {part[3]}, {splits[0]!r} has {classes}")
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]), classes


def dataset_seed(data: Path, default: int) -> int:
    """The seed the dataset in ``data`` was rendered with (its ``summary.json``), else ``default``."""
    summary = data / "summary.json"
    return int(json.loads(summary.read_text()).get("seed", default)) if summary.exists() else default


def argument_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--data", type=Path, default=Path("build/dataset"))
    parser.add_argument("--out", type=Path, default=Path("models/obstacle_classifier.onnx"))
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--epochs", type=int, default=16)
    parser.add_argument("--batch", type=int, default=64)
    parser.add_argument("--lr", type=float, default=3e-3)
    parser.add_argument("--threads", type=int, default=1, help="torch CPU threads")
    parser.add_argument("--train-splits", nargs="+", default=list(TRAIN_SPLITS))
    parser.add_argument("--val-splits", nargs="+", default=list(VAL_SPLITS), help="model selection only")
    parser.add_argument("--widths", type=int, nargs="+", default=list(WIDTHS), help="conv block channels")
    parser.add_argument("--input", choices=INPUTS, default="rgbd", help="colour and depth, or colour only")
    parser.add_argument("--augment", choices=AUGMENTATIONS, default="basic",
                        help="basic: flips, shifts, colour and depth noise; strong: also zoom and occluders")
    return parser


def training_command(args: argparse.Namespace) -> str:
    """The command line that trains this model again: ``--data --seed --epochs --out`` and every option that
    differs from its default (splits, widths, learning rate, ...), in the parser's order."""
    defaults = vars(argument_parser().parse_args([]))
    parts = [TRAIN_COMMAND]
    for name, default in defaults.items():
        value = getattr(args, name)
        if name in ALWAYS_RECORDED or value != default:
            words = value if isinstance(value, list) else [value]
            parts.append(" ".join(["--" + name.replace("_", "-"), *(shlex.quote(str(word)) for word in words)]))
    return " ".join(parts)


def main(argv: List[str]) -> int:  # noqa: PLR0915 - one linear training script
    args = argument_parser().parse_args(argv)
    depth = args.input == "rgbd"

    import torch

    from flex_nav.perception.preprocess import DepthScaling
    from tools.perception.evaluate import evaluate_splits, write_metadata
    from tools.perception.render_dataset import DEPTH_RANGE

    torch.manual_seed(args.seed)
    torch.set_num_threads(args.threads)
    torch.use_deterministic_algorithms(True, warn_only=True)
    gen = torch.Generator().manual_seed(args.seed)

    x_train, y_train, classes = load_splits(args.data, args.train_splits, depth)
    x_val, y_val, val_classes = load_splits(args.data, args.val_splits, depth)
    if val_classes != classes:
        raise ValueError(f"validation classes {val_classes} differ from the training classes {classes}")
    to_tensor = lambda x: torch.from_numpy(x).permute(0, 3, 1, 2).contiguous()  # noqa: E731
    train_images, train_labels = to_tensor(x_train), torch.from_numpy(y_train)
    val_images, val_labels = to_tensor(x_val), torch.from_numpy(y_val)
    channels = train_images.shape[1]
    mean = torch.tensor(MEAN + ((DEPTH_MEAN,) if depth else ())).view(1, channels, 1, 1)
    std = torch.tensor(STD + ((DEPTH_STD,) if depth else ())).view(1, channels, 1, 1)

    model = build_model(len(classes), args.widths, channels)
    params = sum(p.numel() for p in model.parameters())
    optimiser = torch.optim.AdamW(model.parameters(), lr=args.lr, weight_decay=1e-4)
    steps = args.epochs * ((len(train_labels) + args.batch - 1) // args.batch)
    schedule = torch.optim.lr_scheduler.OneCycleLR(optimiser, max_lr=args.lr, total_steps=steps)
    loss_fn = torch.nn.CrossEntropyLoss(label_smoothing=0.05)
    print(f"[train] {len(train_labels)} train / {len(val_labels)} val images, classes {classes}, {params} parameters")

    best: Dict[str, Any] = {"accuracy": -1.0}
    started = time.monotonic()
    for epoch in range(args.epochs):
        model.train()
        order = torch.randperm(len(train_labels), generator=gen)
        total_loss = 0.0
        for i in range(0, len(order), args.batch):
            idx = order[i : i + args.batch]
            images = (augment(train_images[idx], gen, strong=args.augment == "strong") - mean) / std
            loss = loss_fn(model(images), train_labels[idx])
            optimiser.zero_grad()
            loss.backward()
            optimiser.step()
            schedule.step()
            total_loss += float(loss.detach()) * len(idx)
        model.eval()
        with torch.no_grad():
            predicted = model((val_images - mean) / std).argmax(1)
        accuracy = float((predicted == val_labels).float().mean())
        print(f"[train] epoch {epoch + 1}/{args.epochs}: loss {total_loss / len(order):.4f}, "
              f"val accuracy {accuracy:.4f} ({time.monotonic() - started:.0f} s)", flush=True)
        if accuracy > best["accuracy"]:
            best = {"accuracy": accuracy, "epoch": epoch + 1,
                    "state": {k: v.clone() for k, v in model.state_dict().items()}}
    seconds = time.monotonic() - started
    model.load_state_dict(best["state"])
    model.eval()

    export = torch.nn.Sequential(model, torch.nn.Softmax(dim=1)).eval()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    torch.onnx.export(
        export, (torch.zeros(1, channels, x_train.shape[1], x_train.shape[2]),), str(args.out), dynamo=False,
        input_names=["image"], output_names=["probabilities"], dynamic_axes={"image": {0: "batch"},
                                                                            "probabilities": {0: "batch"}},
        opset_version=17,
    )
    print(f"[train] best epoch {best['epoch']} (val accuracy {best['accuracy']:.4f}); {seconds:.0f} s of training; "
          f"wrote {args.out} ({args.out.stat().st_size / 1024:.0f} KiB)")
    training = {
        "dataset_command": DATASET_COMMAND.format(seed=dataset_seed(args.data, args.seed)),
        "command": training_command(args),
        "seed": args.seed,
        "epochs": args.epochs,
        "best_epoch": best["epoch"],
        "train_splits": list(args.train_splits),
        "train_samples": len(train_labels),
        "val_splits": list(args.val_splits),
        "val_accuracy": round(best["accuracy"], 4),
        "widths": list(args.widths),
        "augment": args.augment,
        "parameters": params,
        "seconds": round(seconds, 1),
        "threads": args.threads,
        "torch": torch.__version__.split("+")[0],
    }
    size = (x_train.shape[2], x_train.shape[1])
    depth_input = DepthScaling(DEPTH_RANGE, DEPTH_MEAN, DEPTH_STD) if depth else None
    write_metadata(args.out, classes, MEAN, STD, size, depth=depth_input, training=training)
    results = evaluate_splits(args.out, args.data)
    write_metadata(args.out, classes, MEAN, STD, size, depth=depth_input, training=training, evaluation=results)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
