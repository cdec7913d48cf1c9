"""The static map of a world: walls and tall obstacles, not boxes, people or low obstacles; shipped maps current."""

from __future__ import annotations

from pathlib import Path

import pytest

from flex_nav.nav.costmap.grid_map import FREE, OCCUPIED
from flex_nav.nav.costmap.map_io import load_map
from flex_nav_sim.static_map import shipped_map_path, static_map, write_static_map
from flex_nav_sim.world import available_worlds, load_world


def _value(grid, x: float, y: float) -> int:
    return int(grid.occupancy[grid.world_to_cell(x, y)])


def test_lab_map_content() -> None:
    lab = load_world("lab")
    grid = static_map(lab)
    assert grid.resolution == 0.05
    assert _value(grid, 0.0, 3.0) == OCCUPIED  # west wall
    assert _value(grid, 4.0, 3.0) == OCCUPIED  # island
    assert _value(grid, 7.45, 2.4) == OCCUPIED  # cone
    assert _value(grid, 4.0, 1.0) == FREE  # low step: bumper only, not in the map
    assert _value(grid, 7.55, 5.55) == FREE  # light box: movable, not in the map
    assert _value(grid, 0.4, 5.6) == FREE  # heavy box: movable
    assert _value(grid, 1.0, 1.0) == FREE  # start


def test_people_and_open_doors_not_in_map() -> None:
    grid = static_map(load_world("two_rooms"))
    assert _value(grid, 8.0, 3.2) == FREE  # visitor
    assert _value(grid, 5.0, 2.0) == FREE  # open door
    assert _value(grid, 5.0, 1.0) == OCCUPIED  # divider beside the door


def test_write_and_load_round_trip(tmp_path: Path) -> None:
    world = load_world("corridor")
    path = write_static_map(world, tmp_path / "corridor.yaml")
    loaded = load_map(path)
    grid = static_map(world)
    assert loaded.origin == pytest.approx(grid.origin)
    assert (loaded.occupancy == grid.occupancy).all()


@pytest.mark.parametrize("name", available_worlds())
def test_shipped_maps_are_current(name: str, tmp_path: Path) -> None:
    """sim/worlds/maps/<world>.* must equal a fresh rasterisation (run: python -m flex_nav_sim.static_map --shipped)."""
    shipped = shipped_map_path(name)
    assert shipped.is_file(), f"{shipped} missing: run python -m flex_nav_sim.static_map --shipped"
    fresh = write_static_map(load_world(name), tmp_path / f"{name}.yaml")
    assert fresh.read_text() == shipped.read_text()
    assert (tmp_path / f"{name}.pgm").read_bytes() == shipped.with_suffix(".pgm").read_bytes()
