"""map_server-format load/save: semantics, round trips, the Nav2 benchmark maps and every error path."""

from pathlib import Path

import cv2
import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.costmap.map_io import image_to_occupancy, load_map, save_map

SHARED_MAPS = Path("/work/shared/maps")

YAML_TEMPLATE = """image: {image}
resolution: 0.1
origin: [-1.5, 2.0, 0.0]
negate: {negate}
occupied_thresh: 0.65
free_thresh: 0.196
{extra}"""


def _write(tmp_path, pixels, *, image="m.png", negate=0, extra=""):
    cv2.imwrite(str(tmp_path / image), pixels)
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text(YAML_TEMPLATE.format(image=image, negate=negate, extra=extra))
    return yaml_path


def test_trinary_pgm_flips_rows_and_classifies(tmp_path):
    # Image top row is the map's far edge: after loading it must be the LAST row.
    pixels = np.array([[0, 254, 205], [254, 254, 254]], dtype=np.uint8)
    grid = load_map(_write(tmp_path, pixels, image="m.pgm"))
    assert grid.occupancy.tolist() == [[0, 0, 0], [100, 0, -1]]
    assert grid.resolution == 0.1
    assert grid.origin == (-1.5, 2.0, 0.0)


def test_negate_inverts_grey(tmp_path):
    pixels = np.array([[0, 255, 50]], dtype=np.uint8)
    grid = load_map(_write(tmp_path, pixels, image="m.pgm", negate=1))
    assert grid.occupancy.tolist() == [[0, 100, -1]]


def test_scale_mode_interpolates_and_alpha_zero_is_unknown(tmp_path):
    # occ = (255 - g)/255; g = 128 -> occ 0.498 -> 1 + 98*(0.498-0.196)/(0.65-0.196) = 66.2 -> 66
    bgra = np.array([[[128, 128, 128, 255], [128, 128, 128, 0], [0, 0, 0, 255], [255, 255, 255, 255]]], dtype=np.uint8)
    grid = load_map(_write(tmp_path, bgra, extra="mode: scale\n"))
    assert grid.occupancy.tolist() == [[66, -1, 100, 0]]


def test_trinary_averages_alpha_in(tmp_path):
    # map_server quirk kept: in trinary mode alpha is part of the average: (0+0+0+255)/4 = 63.75 -> occ 0.75 -> 100
    # while (255*3 + 0)/4 = 191.25 -> occ 0.25 -> unknown.
    bgra = np.array([[[0, 0, 0, 255], [255, 255, 255, 0]]], dtype=np.uint8)
    grid = load_map(_write(tmp_path, bgra))
    assert grid.occupancy.tolist() == [[100, -1]]


def test_raw_mode_keeps_values_and_255_is_unknown(tmp_path):
    pixels = np.array([[0, 37, 100, 255]], dtype=np.uint8)
    grid = load_map(_write(tmp_path, pixels, image="m.pgm", extra="mode: raw\n"))
    assert grid.occupancy.tolist() == [[0, 37, 100, -1]]


def test_raw_mode_rejects_values_above_100(tmp_path):
    pixels = np.array([[0, 180]], dtype=np.uint8)
    with pytest.raises(ConfigError, match="raw"):
        load_map(_write(tmp_path, pixels, image="m.pgm", extra="mode: raw\n"))


def test_save_then_load_round_trip(tmp_path):
    rng = np.random.default_rng(4)
    occ = rng.choice(np.array([-1, 0, 100], dtype=np.int8), size=(37, 53))
    grid = GridMap(occ, 0.05, (1.25, -3.5, 0.0))
    image = save_map(grid, tmp_path / "saved.yaml")
    assert image.name == "saved.pgm"
    raw = image.read_bytes()
    assert raw.startswith(b"P5\n")
    back = load_map(tmp_path / "saved.yaml")
    np.testing.assert_array_equal(back.occupancy, occ)
    assert back.resolution == 0.05
    assert back.origin == (1.25, -3.5, 0.0)
    # grey levels written as map_saver does
    assert set(np.unique(cv2.imread(str(image), cv2.IMREAD_UNCHANGED)).tolist()) == {0, 205, 254}


def test_save_thresholds_classify_intermediate_values(tmp_path):
    grid = GridMap(np.array([[0, 25, 26, 64, 65, 100, -1]], dtype=np.int8), 1.0)
    save_map(grid, tmp_path / "t.yaml")
    back = load_map(tmp_path / "t.yaml")
    assert back.occupancy.tolist() == [[0, 0, -1, -1, 100, 100, -1]]


def test_save_rejects_bad_thresholds_and_missing_folder(tmp_path):
    grid = GridMap(np.zeros((2, 2), dtype=np.int8), 1.0)
    with pytest.raises(ConfigError, match="free_threshold"):
        save_map(grid, tmp_path / "t.yaml", occupied_threshold=20, free_threshold=30)
    with pytest.raises(ConfigError, match="does not exist"):
        save_map(grid, tmp_path / "nope" / "t.yaml")


@pytest.mark.parametrize("name", ["100by100_10", "100by100_15", "100by100_20"])
def test_nav2_benchmark_maps(name):
    yaml_path = SHARED_MAPS / f"{name}.yaml"
    if not yaml_path.exists():
        pytest.skip(f"{yaml_path} not present on this machine")
    grid = load_map(yaml_path)
    assert grid.occupancy.shape == (2000, 2000)
    assert grid.resolution == pytest.approx(0.05)
    occupied = float((grid.occupancy == 100).mean())
    expected = int(name.rsplit("_", 1)[1]) / 100.0
    assert abs(occupied - expected) < 0.05, occupied
    assert set(np.unique(grid.occupancy).tolist()) <= {-1, 0, 100}


def test_image_to_occupancy_rejects_bad_mode():
    with pytest.raises(ConfigError, match="trinary"):
        image_to_occupancy(
            np.zeros((2, 2), dtype=np.uint8), negate=False, occupied_thresh=0.65, free_thresh=0.2, mode="bogus"
        )


def test_missing_yaml_names_the_file(tmp_path):
    with pytest.raises(ConfigError, match=r"nope\.yaml"):
        load_map(tmp_path / "nope.yaml")


def test_missing_image_names_field_and_file(tmp_path):
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text(YAML_TEMPLATE.format(image="gone.pgm", negate=0, extra=""))
    with pytest.raises(ConfigError, match=r"field image .*gone\.pgm"):
        load_map(yaml_path)


def test_undecodable_image(tmp_path):
    (tmp_path / "bad.pgm").write_bytes(b"not an image")
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text(YAML_TEMPLATE.format(image="bad.pgm", negate=0, extra=""))
    with pytest.raises(ConfigError, match="cannot decode"):
        load_map(yaml_path)


@pytest.mark.parametrize(
    ("replace", "needle"),
    [
        (("resolution: 0.1", "resolution: -1"), "field resolution"),
        (("resolution: 0.1", "resolution: abc"), "field resolution"),
        (("origin: [-1.5, 2.0, 0.0]", "origin: [1, 2]"), "field origin"),
        (("origin: [-1.5, 2.0, 0.0]", "origin: [1, .nan, 0]"), "origin.y"),
        (("negate: 0", "negate: 2"), r"field negate .*valid: 0, 1"),
        (("occupied_thresh: 0.65", "occupied_thresh: 1.5"), "field occupied_thresh"),
        (("free_thresh: 0.196", "free_thresh: 0.9"), "free_thresh .* below occupied_thresh"),
        (("negate: 0\n", ""), "missing field.*negate"),
        (("image: m.pgm", "image: ''"), "field image"),
    ],
)
def test_bad_fields_raise_config_error_naming_the_field(tmp_path, replace, needle):
    yaml_path = _write(tmp_path, np.zeros((2, 2), dtype=np.uint8), image="m.pgm")
    text = yaml_path.read_text()
    assert replace[0] in text
    yaml_path.write_text(text.replace(*replace))
    with pytest.raises(ConfigError, match=needle) as info:
        load_map(yaml_path)
    assert "m.yaml" in str(info.value)


def test_unknown_mode_lists_choices(tmp_path):
    yaml_path = _write(tmp_path, np.zeros((2, 2), dtype=np.uint8), image="m.pgm", extra="mode: fancy\n")
    with pytest.raises(ConfigError, match=r"mode 'fancy' is not valid \(valid: trinary, scale, raw\)"):
        load_map(yaml_path)


def test_not_a_mapping_and_bad_yaml(tmp_path):
    yaml_path = tmp_path / "m.yaml"
    yaml_path.write_text("- 1\n- 2\n")
    with pytest.raises(ConfigError, match="mapping"):
        load_map(yaml_path)
    yaml_path.write_text("image: [unclosed\n")
    with pytest.raises(ConfigError, match="not valid YAML"):
        load_map(yaml_path)
