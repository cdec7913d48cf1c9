"""The world picture: a PNG with the map, robots and rays; bad input fails with status 2."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from flex_nav_sim.picture import BOX_COLOR, LOW_COLOR, RAY_COLOR, ROBOT_COLORS, _ros_style, main
from flex_nav_sim.static_map import static_map
from flex_nav_sim.world import load_world


def _has_color(image: np.ndarray, bgr: tuple, tolerance: int = 12) -> bool:
    return bool((np.abs(image.astype(int) - np.array(bgr)).max(axis=2) <= tolerance).any())


def test_lab_picture(tmp_path: Path) -> None:
    out = tmp_path / "lab.png"
    assert main(["lab", str(out)]) == 0
    image = cv2.imread(str(out))
    assert image is not None
    grid = static_map(load_world("lab"))  # 4 px per cell, plus title and legend rows
    assert image.shape[0] == grid.height * 4 + 28 + 30
    assert image.shape[1] >= grid.width * 4 and image.shape[1] >= 760
    assert _has_color(image, ROBOT_COLORS[0])  # the robot
    assert _has_color(image, BOX_COLOR) and _has_color(image, LOW_COLOR)
    assert _has_color(image, RAY_COLOR, tolerance=60)  # rays, blended


def test_rosrun_style_arguments() -> None:
    assert _ros_style(["_world:=lab", "out.png", "_seconds:=3", "__name:=x"]) == ["lab", "out.png", "--seconds", "3"]


def test_unknown_world_exit_status(tmp_path: Path, capsys) -> None:
    assert main(["moon", str(tmp_path / "x.png")]) == 2
    assert "world 'moon' is not valid" in capsys.readouterr().err


def test_unwritable_output(tmp_path: Path, capsys) -> None:
    assert main(["corridor", str(tmp_path / "missing" / "x.png")]) == 2
    assert "cannot write the picture" in capsys.readouterr().err
