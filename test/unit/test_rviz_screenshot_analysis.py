"""The checks of flex_nav.apps.rviz_screenshot on made-up pictures: what makes test_rviz_system fail."""

from __future__ import annotations

import math

import numpy as np

from flex_nav.apps.rviz_screenshot import BACKGROUND, analyse, map_to_pixel, ring_coverage, rviz_errors, tinted


def window(view_rgb: np.ndarray) -> np.ndarray:
    """A 300 x 200 screen: a light panel on the left, the 3D view (``view_rgb``, 200 x 200) on the right."""
    screen = np.full((200, 300, 3), 230, dtype=np.uint8)
    screen[:, 100:] = view_rgb
    return screen


def test_an_empty_view_and_no_view_are_problems() -> None:
    empty = analyse(window(np.full((200, 200, 3), BACKGROUND, dtype=np.uint8)))
    assert empty.view == (100, 0, 300, 200)
    assert any(p.startswith("free") for p in empty.problems()) and any("scan" in p for p in empty.problems())
    nothing = analyse(np.full((200, 300, 3), 230, dtype=np.uint8))
    assert nothing.view is None and nothing.problems()


def test_a_drawn_view_has_no_problem() -> None:
    view = np.full((200, 200, 3), BACKGROUND, dtype=np.uint8)
    view[20:180, 20:180] = (192, 192, 192)  # free
    view[20:40, 20:180] = (40, 9, 40)  # lethal (a wall)
    view[40:50, 20:180] = (93, 237, 237)  # inscribed
    view[100, 60:160] = (255, 0, 0)  # scan
    view[120, 40:160] = (0, 170, 0)  # plan
    view[:, ::7] = (82, 82, 83)  # grid lines: many colours would come from anti-aliasing; here only a few
    shown = analyse(window(view))
    assert [p for p in shown.problems() if "distinct colours" not in p] == [], shown.line()
    assert shown.counts["scan"] >= 80 and shown.counts["green"] >= 100


def test_ring_coverage_tells_an_outline_from_a_line() -> None:
    picture = np.full((200, 200, 3), 192, dtype=np.uint8)
    for k in range(360):  # an orange circle of 0.2 m at (50, 50) px, 100 px/m, blended half over the grey
        a = math.radians(k)
        picture[round(50 + 20 * math.sin(a)), round(50 + 20 * math.cos(a))] = (223, 181, 96)
    picture[150, 100:200] = (0, 170, 0)  # a green line through (150, 150)
    assert ring_coverage(picture, (50, 50), 100.0, (255, 170, 0)) > 0.9
    assert ring_coverage(picture, (50, 50), 100.0, (0, 255, 0)) == 0.0  # another robot's colour
    assert ring_coverage(picture, (150, 150), 100.0, (0, 255, 0)) < 0.1
    assert not tinted(np.array([[[255, 0, 0]]], dtype=np.uint8), (255, 170, 0)).any()  # scan red is not orange


def test_map_to_pixel_is_rviz_top_down() -> None:
    assert map_to_pixel((0, 0, 200, 100), 100.0, (4.0, 3.0), 4.0, 3.0) == (100.0, 50.0)
    assert map_to_pixel((0, 0, 200, 100), 100.0, (4.0, 3.0), 4.5, 3.25) == (150.0, 25.0)  # y up


def test_rviz_errors_but_the_known_gl_one() -> None:
    log = ("\x1b[0m[ INFO] [1.0]: rviz version 1.14.19\x1b[0m\n"
           "\x1b[31m[ERROR] [2.0]: rviz/glsl120/indexed_8bit_image.vert\nrviz/glsl120/indexed_8bit_image.frag\n"
           " GLSL link result : \nactive samplers with a different type refer to the same texture image unit\x1b[0m\n"
           "\x1b[0m[ INFO] [3.0]: Creating 1 swatches\x1b[0m\n")
    assert rviz_errors(log) == []
    bad = log + "\x1b[31m[ERROR] [4.0]: PluginlibFactory: The plugin for class 'rviz/Nope' failed to load.\x1b[0m\n"
    assert rviz_errors(bad) == ["[ERROR] [4.0]: PluginlibFactory: The plugin for class 'rviz/Nope' failed to load."]
