"""The classifier's dataset tools (tools/perception): which models go into which split, that every scene
model shows up in the region of interest, and how training concatenates splits. No torch needed."""

from __future__ import annotations

import functools
import importlib
import math
import shlex
import sys
from pathlib import Path

import numpy as np
import pytest
from harness import REPO_ROOT
from unit.perception.onnx_builder import mean_colour_classifier

if str(REPO_ROOT) not in sys.path:  # ``tools`` is imported as a package from the repository root
    sys.path.insert(0, str(REPO_ROOT))

from flex_nav.exceptions import ConfigError
from flex_nav.perception.labels import LABELS
from flex_nav.perception.onnx_model import make_session
from flex_nav.perception.preprocess import roi_patch
from flex_nav.perception.roi import Roi
from tools.perception import ensemble, held_out, render_dataset, scenes, train


def _all(models: dict[str, tuple[str, ...]]) -> set[str]:
    return {m for ms in models.values() for m in ms}


TRAINING_TABLES = (scenes.TRAIN_MODELS, scenes.TRAIN_ONLY, scenes.PASSAGE, scenes.PROCEDURAL, scenes.ASSISTIVE,
                   scenes.ENCUMBERED, scenes.ON_FLOOR, scenes.SAMPLED, scenes.SAMPLED2)


@pytest.mark.parametrize(("held_out_split", "held_out_models"), list(scenes.HELD_OUT_SETS.items()))
def test_held_out_models_never_reach_another_split(held_out_split: str,
                                                   held_out_models: dict[str, tuple[str, ...]]) -> None:
    held_out = _all(held_out_models)
    for split in render_dataset.SPLITS:
        used = _all(scenes.models_for(split))
        if split == held_out_split:
            assert used == held_out
        else:
            assert not used & held_out, f"{split} uses held-out models {sorted(used & held_out)}"


def test_training_and_selection_read_no_held_out_split() -> None:
    for split in (*train.TRAIN_SPLITS, *train.VAL_SPLITS):
        assert split in render_dataset.SPLITS
        assert not split.startswith(("test", "unseen")), split


def test_extra_splits_add_the_training_only_models_to_the_seen_ones() -> None:
    for split in scenes.EXTRA_SPLITS:
        assert split in render_dataset.SPLITS
    for split in ("extra", "val_extra"):
        models = scenes.models_for(split)
        for label in LABELS:
            assert models[label] == scenes.TRAIN_MODELS[label] + scenes.TRAIN_ONLY[label]
    assert scenes.models_for("train") == scenes.TRAIN_MODELS  # the original splits are unchanged
    assert not _all(scenes.TRAIN_ONLY) & _all(scenes.TRAIN_MODELS)


def test_split_ids_are_unique_so_every_split_has_its_own_scenes() -> None:
    ids = [split_id for split_id, _ in render_dataset.SPLITS.values()]
    assert len(ids) == len(set(ids))


def test_every_model_has_a_builder_and_every_builder_is_used() -> None:
    listed = set().union(*(_all(t) for t in (*TRAINING_TABLES, *scenes.HELD_OUT_SETS.values())))
    assert listed == set(scenes.BUILDERS)
    assert set(scenes.SIDE_DISTRACTORS) <= _all(scenes.TRAIN_MODELS)


def test_a_held_out_model_named_like_a_training_model_stops_the_import(monkeypatch: pytest.MonkeyPatch) -> None:
    """A held-out 'pillar' once replaced the seen one in BUILDERS for two minutes of a render; it must not load."""
    clash = {**held_out.HELD_OUT_BUILDERS, "pillar": held_out.HELD_OUT_BUILDERS["structural_pillar"]}
    monkeypatch.setattr(held_out, "HELD_OUT_BUILDERS", clash)
    try:
        with pytest.raises(ConfigError, match=r"\['pillar'\]"):
            importlib.reload(scenes)
    finally:
        monkeypatch.undo()
        importlib.reload(scenes)
    assert scenes.BUILDERS["pillar"] is scenes.clear_pillar


def test_the_held_out_registry_keeps_the_order_registered_and_refuses_bad_entries(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Splits come out in the order of their number, a label's models in the order registered; a name used twice,
    a split not named like the held-out ones, a label that is not one, a split missing a label: each stops it."""
    monkeypatch.setattr(held_out.registry, "_MODELS", {})
    monkeypatch.setattr(held_out.registry, "_BUILDERS", {})

    def build(sc: object, x: float, y: float, yaw: float) -> None:
        pass

    for split, label, model in (("unseen10", "person", "p10"), ("unseen2", "clear", "c2b"), ("unseen", "person", "p1"),
                                ("unseen2", "clear", "c2a"), ("unseen2", "person", "p2"), ("unseen2", "movable", "m2"),
                                ("unseen", "movable", "m1"), ("unseen", "clear", "c1"), ("unseen10", "movable", "m10"),
                                ("unseen10", "clear", "c10")):
        assert held_out.held_out(split, label, model)(build) is build
    assert list(held_out.registry.sets()) == ["unseen", "unseen2", "unseen10"]
    assert held_out.registry.sets()["unseen2"] == {"person": ("p2",), "movable": ("m2",), "clear": ("c2b", "c2a")}
    assert set(held_out.registry.builders()) == {"p1", "m1", "c1", "p2", "m2", "c2a", "c2b", "p10", "m10", "c10"}
    with pytest.raises(ConfigError, match="'p2' is already registered; give the one in 'unseen3' another name"):
        held_out.held_out("unseen3", "person", "p2")(build)
    with pytest.raises(ConfigError, match="the split 'unseen1' is not named"):
        held_out.held_out("unseen1", "person", "x")
    with pytest.raises(ConfigError, match="label 'chair' is not valid"):
        held_out.held_out("unseen3", "chair", "x")
    held_out.held_out("unseen3", "person", "p3")(build)
    with pytest.raises(ConfigError, match=r"'unseen3' has no model of \['movable', 'clear'\]"):
        held_out.registry.sets()


def test_plan_cycles_the_models_of_the_extra_split_evenly() -> None:
    rng = np.random.default_rng(0)
    movable = scenes.models_for("extra")["movable"]
    pairs = scenes.plan(LABELS, 2 * len(movable), "extra", rng)
    assert len(pairs) == 2 * len(movable) * len(LABELS)
    counts = {m: sum(1 for label, model in pairs if model == m and label == "movable") for m in movable}
    assert set(counts.values()) == {2}


@functools.lru_cache(maxsize=1)
def _empty_roi() -> np.ndarray:
    return _roi_of(None)


def _roi_of(model: str | None) -> np.ndarray:
    """The default ROI of a TurtleBot 4 camera image of a floor and ``model`` 1.4 m ahead (fixed light)."""
    renderer = scenes.Renderer(np.random.default_rng(0))
    try:
        renderer.client.resetSimulation()
        scene = scenes.Scene(renderer.client, np.random.default_rng(1))
        scene.floor((0.5, 0.5, 0.5, 1.0))
        spec = renderer.cameras["turtlebot4"]
        assert spec is not None
        if model is not None:
            scenes.BUILDERS[model](scene, spec.mount[0] + 1.4, 0.0, math.radians(20.0))
        renderer.rng = np.random.default_rng(2)  # the same light for both pictures
        rgb, _ = renderer._shoot(spec, (spec.mount[0], 0.0, spec.mount[2]), spec.pitch)
    finally:
        renderer.close()
    return roi_patch(rgb, Roi(), 64, 64).astype(np.int16)


ADDED_MODELS = sorted(set().union(*(_all(t) for t in (*TRAINING_TABLES[1:], *scenes.HELD_OUT_SETS.values())))
                      - _all(scenes.TRAIN_MODELS) - _all(scenes.HELD_OUT_SETS["unseen"]))


@pytest.mark.parametrize("model", ADDED_MODELS)
def test_every_added_model_is_visible_in_the_roi(model: str) -> None:
    changed = np.abs(_roi_of(model) - _empty_roi()).max(axis=2) > 10
    assert changed.mean() > 0.03, f"{model} changes only {100 * changed.mean():.1f} % of the ROI"


@pytest.mark.parametrize("argv", [
    ["--seed", "11", "--epochs", "24", "--out", "build/my models/seed11.onnx"],
    ["--seed", "9", "--input", "rgb", "--lr", "0.001", "--widths", "8", "16",
     "--train-splits", "train", "extra2", "extra2", "--val-splits", "val"],
])
def test_the_recorded_training_command_trains_the_same_model_again(argv: list[str]) -> None:
    args = train.argument_parser().parse_args(argv)
    command = train.training_command(args)
    assert command.startswith(train.TRAIN_COMMAND + " ")
    again = train.argument_parser().parse_args(shlex.split(command[len(train.TRAIN_COMMAND):]))
    assert vars(again) == vars(args)
    assert ("--input" in command) == ("--input" in argv)  # options at their defaults are left out


def test_load_splits_concatenates_and_checks_the_classes(tmp_path: Path) -> None:
    for name, n, names in (("a", 3, LABELS), ("b", 2, LABELS), ("c", 1, ("x", "y"))):
        np.savez(tmp_path / f"{name}.npz", patches=np.full((n, 4, 4, 3), 51 * n, np.uint8),
                 depths=np.full((n, 4, 4), 1000 * n, np.uint16), labels=np.arange(n), models=np.array(["m"] * n),
                 classes=np.array(names))
    np.savez(tmp_path / "old.npz", patches=np.zeros((1, 4, 4, 3), np.uint8), labels=np.arange(1),
             models=np.array(["m"]), classes=np.array(LABELS))
    images, labels, classes = train.load_splits(tmp_path, ["a", "b"], depth=False)
    assert images.shape == (5, 4, 4, 3)
    assert images[0, 0, 0, 0] == pytest.approx(0.6) and images[-1, 0, 0, 0] == pytest.approx(0.4)
    assert labels.tolist() == [0, 1, 2, 0, 1]
    assert classes == list(LABELS)
    images, _, _ = train.load_splits(tmp_path, ["a", "b"], depth=True)
    assert images.shape == (5, 4, 4, 4)
    metres = images[:, 0, 0, 3] * render_dataset.DEPTH_RANGE  # depth channel = depth / DEPTH_RANGE
    np.testing.assert_allclose(metres, [3.0, 3.0, 3.0, 2.0, 2.0], rtol=1e-6)
    with pytest.raises(ValueError, match="'c' has classes"):
        train.load_splits(tmp_path, ["a", "c"], depth=False)
    with pytest.raises(ValueError, match=r"split 'old' .* has no depth patches"):
        train.load_splits(tmp_path, ["old"], depth=True)


def test_depth_augmentation_loses_returns_as_real_cameras_do() -> None:
    torch = pytest.importorskip("torch")  # training-only dependency: skipped in the runtime venv
    gen = torch.Generator().manual_seed(0)
    depth = torch.full((400, 1, 16, 16), 2.0 / render_dataset.DEPTH_RANGE)  # 2 m everywhere
    depth[:, :, 12:] = 0.4 / render_dataset.DEPTH_RANGE  # the floor 0.4 m ahead at the bottom
    depth[:, :, :2] = 1.0  # nothing in range at the top
    out = train.augment_depth(depth, gen)
    assert out.shape == depth.shape and float(out.min()) >= 0.0 and float(out.max()) <= 1.0
    assert bool((out[:, :, :2] == 1.0).all())  # lost stays lost
    middle = out[:, :, 4:10] * render_dataset.DEPTH_RANGE
    kept = middle[middle < 3.9]
    assert 1.8 < float(kept.mean()) < 2.2 and 0.02 < float(kept.std()) < 0.2  # scale error and noise, about 2 m
    lost_near = (out[:, :, 12:] == 1.0).flatten(1).float().mean(1)
    assert 0.15 < float((lost_near > 0.99).float().mean()) < 0.45  # some frames lose the near floor (min range)
    assert float((middle >= 3.99).float().mean()) < 0.05  # scattered holes only


def test_zoom_keeps_size_and_depth_consistent_and_occluders_paint_rectangles() -> None:
    torch = pytest.importorskip("torch")  # training-only dependency: skipped in the runtime venv
    gen = torch.Generator().manual_seed(0)
    batch = torch.zeros((200, 4, 64, 64))
    batch[:, 3] = 1.0  # nothing in range ...
    batch[:, :3, 24:40, 24:40] = 0.8  # ... but a bright square 2 m away in the middle
    batch[:, 3, 24:40, 24:40] = 2.0 / render_dataset.DEPTH_RANGE
    zoomed = train.augment_zoom(batch, gen)
    square = zoomed[:, 0] > 0.4
    sides_px = square.float().sum((1, 2)).sqrt()
    near_m = torch.where(zoomed[:, 3] < 0.999, zoomed[:, 3], torch.nan).nanmean((1, 2)) * render_dataset.DEPTH_RANGE
    assert float(sides_px.min()) > 13.0 and float(sides_px.max()) < 19.0 and float(sides_px.std()) > 0.5
    np.testing.assert_allclose((sides_px * near_m).numpy(), 32.0, rtol=0.1)  # bigger = nearer (pinhole)
    assert bool((zoomed[:, 3, :12] == 1.0).all()) and bool((zoomed[:, 3, -12:] == 1.0).all())  # lost stays lost

    occluded = train.augment_occlusion(batch, gen)
    changed = (occluded != batch).any(1)
    share = float(changed.flatten(1).any(1).float().mean())
    assert 0.35 < share < 0.65
    for image, mask in zip(occluded, changed):
        if mask.any():
            rows, cols = mask.any(1).nonzero().flatten(), mask.any(0).nonzero().flatten()
            box = image[:, rows.min() : rows.max() + 1, cols.min() : cols.max() + 1]
            assert box.shape[1] <= 22 and box.shape[2] <= 22
            assert bool((box == box[:, :1, :1]).all())  # one colour and one depth


def test_ensemble_averages_the_members_probabilities(tmp_path: Path) -> None:
    weights = (10.0 * np.eye(3), np.array([[0.0, 5.0, 0.0], [0.0, 0.0, 5.0], [5.0, 0.0, 0.0]]))
    members = [mean_colour_classifier(tmp_path / f"m{k}.onnx", w) for k, w in enumerate(weights)]
    out = tmp_path / "ensemble.onnx"
    out.write_bytes(ensemble.combine(members).SerializeToString())
    image = np.random.default_rng(0).uniform(0.0, 1.0, (4, 3, 8, 8)).astype(np.float32)

    def run(path: Path) -> np.ndarray:
        scores: np.ndarray = make_session(path).run(None, {"image": image})[0]
        return scores

    expected = (run(members[0]) + run(members[1])) / 2.0
    np.testing.assert_allclose(run(out), expected, rtol=1e-5)
    with pytest.raises(ValueError, match="at least 2 members"):
        ensemble.combine(members[:1])


def test_dataset_seed_comes_from_the_dataset_summary(tmp_path: Path) -> None:
    assert train.dataset_seed(tmp_path, 8) == 8  # no summary: the training seed
    (tmp_path / "summary.json").write_text('{"seed": 7, "train": {"samples": 3}}')
    assert train.dataset_seed(tmp_path, 8) == 7
