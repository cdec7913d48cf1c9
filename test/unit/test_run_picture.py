from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
import pytest

from flex_nav.apps.run_picture import HIT_COLOUR, RobotTrack, draw_run, write_png
from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import GridMap


def _grid() -> GridMap:
    occ = np.zeros((40, 60), dtype=np.int8)
    occ[0, :] = 100  # a wall along the bottom row (y = origin)
    return GridMap(occ, 0.1, (-1.0, -1.0, 0.0))


def test_walls_at_the_bottom_trajectory_and_hit_drawn(tmp_path: Path) -> None:
    track = RobotTrack("robot1", trajectory=[(0.0, 0.0), (3.0, 1.0)], plans=[np.array([[0.0, 0.0], [3.0, 1.0]])],
                       goals=[(3.0, 1.0)], bumper_hits=[(1.5, 2.0)])
    img = draw_run(_grid(), [track], px_per_cell=2)[44:]  # below the title band
    assert img.shape == (80, 120, 3)
    assert (img[-1, 60] == 0).all() and (img[-2, 60] == 0).all()  # map row 0 -> picture bottom
    # the bumper hit circle: red pixels around (1.5, 2.0) -> grid (25, 30) -> pixel (50, 80 - 60 = 20)
    patch = img[10:31, 40:61].reshape(-1, 3)
    assert any(tuple(p) == HIT_COLOUR for p in patch)
    out = tmp_path / "run.png"
    write_png(out, img)
    assert cv2.imread(str(out)).shape == (img.shape[0], img.shape[1], 3)


def test_costmap_shape_must_match() -> None:
    with pytest.raises(ConfigError, match="costmap shape"):
        draw_run(_grid(), [], costmap=np.zeros((3, 3), dtype=np.int8))
