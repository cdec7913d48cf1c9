"""Image buffers -> RGB and depth, the region of interest, the classifier patches and the YOLO letterbox."""

from __future__ import annotations

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.perception.image import to_depth, to_rgb
from flex_nav.perception.preprocess import (
    LETTERBOX_PAD,
    DepthScaling,
    Letterbox,
    Normaliser,
    depth_patch,
    letterbox,
    roi_patch,
)
from flex_nav.perception.roi import Roi


def _rgb(h: int = 4, w: int = 6) -> np.ndarray:
    return np.arange(h * w * 3, dtype=np.uint8).reshape(h, w, 3)


def test_rgb8_packed_is_returned_unchanged() -> None:
    img = _rgb()
    out = to_rgb(img.tobytes(), 6, 4, "rgb8")
    assert out.shape == (4, 6, 3)
    np.testing.assert_array_equal(out, img)


def test_bgr8_and_bgra8_are_reordered_to_rgb() -> None:
    img = _rgb()
    np.testing.assert_array_equal(to_rgb(img[:, :, ::-1].tobytes(), 6, 4, "bgr8"), img)
    bgra = np.concatenate([img[:, :, ::-1], np.full((4, 6, 1), 255, np.uint8)], axis=2)
    np.testing.assert_array_equal(to_rgb(bgra.tobytes(), 6, 4, "bgra8"), img)
    rgba = np.concatenate([img, np.zeros((4, 6, 1), np.uint8)], axis=2)
    np.testing.assert_array_equal(to_rgb(rgba.tobytes(), 6, 4, "rgba8"), img)


def test_mono8_is_grey_rgb() -> None:
    grey = np.arange(24, dtype=np.uint8).reshape(4, 6)
    out = to_rgb(grey.tobytes(), 6, 4, "mono8")
    assert out.shape == (4, 6, 3)
    for c in range(3):
        np.testing.assert_array_equal(out[:, :, c], grey)


def test_padded_rows_are_cut_by_step() -> None:
    img = _rgb()
    padded = np.zeros((4, 6 * 3 + 5), dtype=np.uint8)
    padded[:, : 6 * 3] = img.reshape(4, -1)
    padded[:, 6 * 3 :] = 77
    out = to_rgb(padded.tobytes(), 6, 4, "bgr8", step=23)
    np.testing.assert_array_equal(out, img[:, :, ::-1])


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        ((b"\0" * 72, 6, 4, "rgb16"), "encoding 'rgb16' is not valid (valid: rgb8, bgr8, rgba8, bgra8, mono8)"),
        ((b"\0" * 71, 6, 4, "rgb8"), "71 bytes"),
        ((b"\0" * 72, 6, 4, "rgb8", 10), "step 10 is shorter than a row"),
        ((b"", 0, 4, "rgb8"), "must be positive"),
    ],
)
def test_bad_buffers_are_rejected_with_the_reason(args: tuple, needle: str) -> None:
    with pytest.raises(ConfigError) as err:
        to_rgb(*args)
    assert needle in str(err.value)


def test_roi_validation_names_the_problem() -> None:
    with pytest.raises(ConfigError, match="x_min < x_max"):
        Roi(0.8, 0.0, 0.2, 1.0)
    with pytest.raises(ConfigError, match=r"fractions in \[0, 1\]"):
        Roi(-0.1, 0.0, 0.5, 1.0)
    with pytest.raises(ConfigError, match=r"my_roi = \[0.1, 0.2\] must be a list of 4"):
        Roi.from_sequence([0.1, 0.2], "my_roi")
    with pytest.raises(ConfigError, match="must hold numbers"):
        Roi.from_sequence(["a", 0, 1, 1])  # type: ignore[list-item]  # the wrong type is the test


def test_roi_pixels_crop_and_overlap() -> None:
    roi = Roi(0.25, 0.5, 0.75, 1.0)
    assert roi.pixels(320, 240) == (80, 120, 240, 240)
    img = np.zeros((240, 320, 3), np.uint8)
    assert roi.crop(img).shape == (120, 160, 3)
    assert roi.overlap((80, 120, 240, 240), 320, 240) == pytest.approx(1.0)
    assert roi.overlap((0, 0, 80, 120), 320, 240) == 0.0
    assert roi.overlap((0, 120, 160, 240), 320, 240) == pytest.approx(0.5)  # half the box is inside
    assert roi.overlap((10, 10, 10, 50), 320, 240) == 0.0  # empty box
    with pytest.raises(ConfigError, match="less than 2 px"):
        Roi(0.5, 0.0, 0.501, 1.0).pixels(320, 240)


def test_roi_patch_takes_only_the_region_and_resizes() -> None:
    img = np.zeros((240, 320, 3), np.uint8)
    img[:, :64] = (255, 0, 0)  # left 20 %: outside the default roi
    img[:, 64:256] = (0, 200, 0)  # the roi
    img[:, 256:] = (0, 0, 255)
    patch = roi_patch(img, Roi(), 64, 64)
    assert patch.shape == (64, 64, 3) and patch.dtype == np.uint8
    assert (patch == (0, 200, 0)).all()


def test_normaliser_matches_the_formula() -> None:
    norm = Normaliser((0.5, 0.25, 0.0), (0.25, 0.5, 1.0))
    patch = np.zeros((2, 3, 3), np.uint8)
    patch[..., 0], patch[..., 1], patch[..., 2] = 255, 51, 102
    out = norm.batch(np.stack([patch, patch]))
    assert out.shape == (2, 3, 2, 3) and out.dtype == np.float32
    np.testing.assert_allclose(out[1, 0], (1.0 - 0.5) / 0.25, rtol=1e-6)
    np.testing.assert_allclose(out[1, 1], (0.2 - 0.25) / 0.5, rtol=1e-5)
    np.testing.assert_allclose(out[1, 2], 0.4, rtol=1e-5)
    np.testing.assert_allclose(out[0], out[1], rtol=1e-6)
    with pytest.raises(ConfigError, match="must be finite and > 0"):
        Normaliser((0.5, 0.5, 0.5), (0.25, 0.0, 0.25))


def test_letterbox_of_a_wide_image_pads_top_and_bottom() -> None:
    img = np.full((240, 320, 3), 10, np.uint8)
    tensor, box = letterbox(img, 64, 64)
    assert tensor.shape == (1, 3, 64, 64) and tensor.dtype == np.float32
    assert box == Letterbox(320, 240, 0.2, 0.0, 8.0)
    pad, image = LETTERBOX_PAD / 255.0, 10 / 255.0
    np.testing.assert_allclose(tensor[0, :, :8], pad, rtol=1e-6)
    np.testing.assert_allclose(tensor[0, :, 56:], pad, rtol=1e-6)
    np.testing.assert_allclose(tensor[0, :, 8:56], image, rtol=1e-6)


def test_letterbox_of_a_tall_image_pads_left_and_right() -> None:
    img = np.zeros((200, 100, 3), np.uint8)
    _, box = letterbox(img, 64, 64)
    assert box.scale == pytest.approx(0.32)
    assert (box.pad_x, box.pad_y) == (16.0, 0.0)


def test_letterbox_maps_boxes_back_to_the_image_and_clips() -> None:
    box = Letterbox(320, 240, 0.2, 0.0, 8.0)
    out = box.to_image(np.array([[24.0, 24.0, 40.0, 40.0], [-5.0, 0.0, 70.0, 64.0]], np.float32))
    np.testing.assert_allclose(out[0], (120.0, 80.0, 200.0, 160.0))
    np.testing.assert_allclose(out[1], (0.0, 0.0, 320.0, 240.0))  # the padding maps outside: clipped


# -- depth images (REP 118) ------------------------------------------------------------------------------
def test_32fc1_is_metres_and_16uc1_millimetres() -> None:
    metres = np.array([[0.5, 1.25, np.inf], [np.nan, 0.0, 3.0]], np.float32)
    np.testing.assert_array_equal(to_depth(metres.tobytes(), 3, 2, "32FC1"), metres)
    mm = np.array([[500, 1250, 0], [0, 65535, 3000]], np.uint16)
    np.testing.assert_allclose(to_depth(mm.tobytes(), 3, 2, "16UC1"), mm.astype(np.float32) / 1000.0, rtol=1e-6)
    assert to_depth(mm.tobytes(), 3, 2, "16UC1").dtype == np.float32


def test_depth_rows_may_be_padded_and_big_endian() -> None:
    values = np.array([[1.0, 2.0], [3.0, 4.0]], np.float32)
    padded = np.zeros((2, 4), ">f4")  # 2 px + 2 px of padding per row, big-endian
    padded[:, :2] = values
    out = to_depth(padded.tobytes(), 2, 2, "32FC1", step=16, bigendian=True)
    np.testing.assert_array_equal(out, values)


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        ((bytes(8), 2, 1, "mono8"), "depth image encoding 'mono8' is not valid (valid: 32FC1, 16UC1)"),
        ((bytes(8), 0, 1, "32FC1"), "depth image size 0x1"),
        ((bytes(4), 2, 1, "32FC1"), "has 4 bytes, 8 x 1 = 8 expected"),
        ((bytes(12), 2, 1, "32FC1", 4), "depth image step 4 is shorter than a row (2 px x 4 bytes = 8)"),
        ((bytes(12), 2, 1, "32FC1", 10), "depth image step 10 is not a multiple of the 4 bytes of a pixel"),
    ],
)
def test_bad_depth_images_are_named(args: tuple, needle: str) -> None:
    with pytest.raises(ConfigError) as err:
        to_depth(*args)
    assert needle in str(err.value)


def test_depth_patch_counts_missing_and_far_returns_as_the_range_limit() -> None:
    depth = np.full((4, 10), 1.0, np.float32)
    depth[0, 2] = np.nan
    depth[1, 3] = 0.0
    depth[2, 4] = -np.inf
    depth[3, 5] = np.inf
    depth[3, 6] = 9.0
    patch = depth_patch(depth, Roi(0.2, 0.0, 0.8, 1.0), 6, 4, max_range=4.0)  # columns 2..7, same size
    expected = np.full((4, 6), 1.0, np.float32)
    expected[0, 0] = expected[1, 1] = expected[2, 2] = expected[3, 3] = expected[3, 4] = 4.0
    np.testing.assert_array_equal(patch, expected)
    small = depth_patch(depth, Roi(0.2, 0.0, 0.8, 1.0), 3, 2, max_range=4.0)  # area average of 2 x 2 blocks
    np.testing.assert_allclose(small, [[2.5, 1.0, 1.0], [1.0, 2.5, 1.75]])
    assert small.dtype == np.float32


def test_depth_scaling_and_its_checks() -> None:
    scaling = DepthScaling(max_range=4.0, mean=0.5, std=0.25)
    patch = np.array([[0.0, 2.0], [4.0, 1.0]], np.float32)
    out = scaling.batch(np.stack([patch, patch]))
    assert out.shape == (2, 1, 2, 2) and out.dtype == np.float32
    np.testing.assert_allclose(out[1, 0], [[-2.0, 0.0], [2.0, -1.0]])
    with pytest.raises(ConfigError, match=r"depth max_range 0\.0 must be a finite number of metres > 0"):
        DepthScaling(0.0, 0.5, 0.25)
    with pytest.raises(ConfigError, match=r"depth std -1.0 must be finite and > 0, mean 0.5 finite"):
        DepthScaling(4.0, 0.5, -1.0)
