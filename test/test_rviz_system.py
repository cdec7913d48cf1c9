"""RViz itself on the demo: Debian's rviz with rviz/flex_nav.rviz (one robot) and rviz/multi_robot.rviz (two robots)
under Xvfb, screenshots checked pixel by pixel.

Each config is shown once (module-scoped fixtures) by the README's own command,
``python -m flex_nav.apps.rviz_screenshot OUT.png`` in a subprocess with a wall bound: it starts the demo's stack
on a private master, sends every robot its first goal, starts Xvfb on a free display and RViz on it, and takes
screenshots until the robots have driven and the view shows everything. The tests then read the picture themselves:
the 3D view is there and not blank, the map's free and occupied cells (lethal costmap cells over them) in their
colours, the scan, the footprint following the robot and the global plan drawn; RViz ran to the end and logged no
ERROR (an unknown display class, a config it cannot parse, a topic of the wrong type are ERRORs). With RViz missing
the command fails with "rviz ... not installed: run tools/install.sh", and so do the tests. A last test runs RViz
without the stack and checks that the displays of a bumper contact, a tracked person and the classifier's class
text draw what ``rostopic pub`` sends them (the demo's run shows none of them).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any, Dict, List, Tuple

import pytest

from flex_nav.apps.rviz_screenshot import analyse, map_to_pixel, read_png, ring_coverage, rviz_errors

REPO_ROOT = Path(__file__).resolve().parents[1]
COMMAND_TIMEOUT_S = 420.0  # [s] wall bound of one screenshot command (the stack, RViz, the drive)
pytestmark = [pytest.mark.ros]

Shown = Tuple[Path, Dict[str, Any], str]  # (the picture, the command's report, RViz's log)


def show(tmp: Path, robots: int) -> Shown:
    picture, report = tmp / "rviz.png", tmp / "report.json"
    cmd = [sys.executable, "-m", "flex_nav.apps.rviz_screenshot", str(picture), "--robots", str(robots),
           "--work", str(tmp / "work"), "--report", str(report)]
    try:
        done = subprocess.run(cmd, cwd=REPO_ROOT, capture_output=True, text=True, timeout=COMMAND_TIMEOUT_S,
                              check=False)
    except subprocess.TimeoutExpired as err:
        pytest.fail(f"{' '.join(cmd)} took over {COMMAND_TIMEOUT_S:.0f} s: {err.stdout!r}")
    assert report.is_file() and picture.is_file(), (
        f"no picture (exit {done.returncode}): {done.stderr[-2000:]}\n{done.stdout[-2000:]}")
    rviz_log = tmp / "work" / "logs" / "rviz.log"
    return picture, json.loads(report.read_text()), rviz_log.read_text(errors="replace")


@pytest.fixture(scope="module")
def one_robot(tmp_path_factory: pytest.TempPathFactory) -> Shown:
    return show(tmp_path_factory.mktemp("rviz_one"), 1)


@pytest.fixture(scope="module")
def two_robots(tmp_path_factory: pytest.TempPathFactory) -> Shown:
    return show(tmp_path_factory.mktemp("rviz_two"), 2)


def check_view(shown: Shown, robots: int) -> None:
    picture, facts, _ = shown
    view = analyse(read_png(picture))
    assert view.view is not None, f"no 3D view in {picture}"
    x0, y0, x1, y1 = view.view
    assert (x1 - x0) * (y1 - y0) > 0.4 * view.size[0] * view.size[1], f"3D view {view.view} too small"
    assert view.distinct_colours > 100, f"the view is nearly blank: {view.line()}"
    assert view.share("free") > 0.15, f"the map's free cells are missing: {view.line()}"
    assert view.share("obstacle") > 0.02, f"the map's occupied cells are missing: {view.line()}"
    assert view.share("inscribed") > 0.01, f"the costmaps' inflation is missing: {view.line()}"
    assert view.counts["scan"] > 100 * robots, f"the scan is missing: {view.line()}"
    assert view.problems() == [], view.problems()
    assert len(facts["driven_m"]) == robots and min(facts["driven_m"]) >= 0.8, facts
    assert all(plans >= 1 for plans in facts["plans"]), f"a robot published no global plan: {facts}"


def footprint_rings(shown: Shown) -> List[float]:
    """Per robot: the coverage of a ring of its footprint's colour around its pose at the picture."""
    picture, facts, _ = shown
    rgb = read_png(picture)
    view = analyse(rgb).view
    assert view is not None
    scale, centre = facts["view_scale"], tuple(facts["view_centre"])
    assert all(pose is not None for pose in facts["poses"]), facts
    return [ring_coverage(rgb, map_to_pixel(view, scale, centre, pose[0], pose[1]), scale, tuple(colour))
            for pose, colour in zip(facts["poses"], facts["footprint_colours"])]


def test_one_robot_view_shows_map_costmaps_scan_and_plan(one_robot: Shown) -> None:
    check_view(one_robot, 1)


def test_one_robot_footprint_is_drawn_around_the_robot(one_robot: Shown) -> None:
    # RViz places a polygon where its frame is when the polygon arrives: a footprint sent once (latched) stayed
    # where the robot was when RViz started, and none was drawn around the robot at its goal
    [at_robot] = footprint_rings(one_robot)
    assert at_robot >= 0.6, f"no footprint outline around the robot (ring coverage {at_robot:.2f})"


def test_one_robot_rviz_ran_without_errors(one_robot: Shown) -> None:
    _, facts, log = one_robot
    assert facts["rviz_running"], f"rviz ended before the picture: {log[-2000:]}"
    assert "rviz version 1.14" in log, f"not RViz 1.14's log: {log[:500]}"
    assert rviz_errors(log) == [], rviz_errors(log)


def test_two_robots_in_multi_robot_config(two_robots: Shown) -> None:
    check_view(two_robots, 2)
    _, facts, log = two_robots
    assert facts["rviz_running"] and rviz_errors(log) == [], rviz_errors(log)
    for robot, at_robot in enumerate(footprint_rings(two_robots), 1):
        assert at_robot >= 0.6, f"robot{robot}: no footprint outline around it (ring coverage {at_robot:.2f})"


MARKER_TOPICS = [  # (topic, type, message): what the new displays of flex_nav.rviz show, placed in the map frame
    ("/robot1/bumper_hits", "geometry_msgs/PointStamped", "{header: {frame_id: map}, point: {x: 2.0, y: 2.0}}"),
    ("/robot1/pure_pursuit_path/people", "geometry_msgs/PoseArray",
     "{header: {frame_id: map}, poses: [{position: {x: 6.0, y: 4.0}, orientation: {w: 1.0}}]}"),
    ("/robot1/obstacle_class_marker", "visualization_msgs/Marker",
     "{header: {frame_id: map}, ns: obstacle_class, type: 9, action: 0, pose: {position: {x: 2.0, y: 5.0}, "
     "orientation: {w: 1.0}}, scale: {z: 0.4}, color: {r: 0.35, g: 1.0, b: 0.35, a: 1.0}, text: 'movable 0.93 (5/5)'}"),
    ("/robot1/get_path_server/global_costmap/obstacle_memory", "visualization_msgs/MarkerArray",  # as memory_markers
     "{markers: [{header: {frame_id: map}, action: 3}, {header: {frame_id: map}, ns: footprint, id: 1, type: 4, "
     "action: 0, pose: {orientation: {w: 1.0}}, scale: {x: 0.04}, color: {r: 0.55, a: 1.0}, points: [{x: 3.8, "
     "y: 0.8}, {x: 4.2, y: 0.8}, {x: 4.2, y: 1.2}, {x: 3.8, y: 1.2}, {x: 3.8, y: 0.8}]}, {header: {frame_id: map}, "
     "ns: text, id: 1, type: 9, action: 0, pose: {position: {x: 4.0, y: 1.0, z: 0.3}, orientation: {w: 1.0}}, "
     "scale: {z: 0.15}, color: {r: 0.55, a: 1.0}, text: '#1 heavy at (4.00, 1.00) m'}]}"),
]


def test_marker_displays_draw_their_topics(tmp_path: Path) -> None:
    """RViz with flex_nav.rviz and no stack: a bumper contact, a tracked person, a class text and a remembered
    obstacle published by ``rostopic pub`` are drawn where they are, in their displays' colours."""
    import time  # noqa: PLC0415

    from flex_nav.apps.rviz_screenshot import SCREEN, checked_setup, tinted, view_geometry  # noqa: PLC0415
    from flex_nav.testing.private_master import PrivateMaster  # noqa: PLC0415
    from flex_nav.testing.process import ManagedProcess  # noqa: PLC0415
    from flex_nav.testing.xvfb import VirtualDisplay  # noqa: PLC0415

    config = checked_setup(REPO_ROOT / "rviz" / "flex_nav.rviz")
    scale, centre = view_geometry(config)
    wanted = {"bumper contact": ((2.0, 2.0), (255, 0, 255)), "person": ((6.0, 4.0), (255, 255, 0)),
              "class text": ((2.0, 5.0), (89, 255, 89)),
              "remembered obstacle": ((4.0, 1.0), (140, 0, 0))}  # (map point [m], colour)
    found: Dict[str, int] = {}
    with PrivateMaster(ros_home=tmp_path / "ros_home") as master, \
            VirtualDisplay(*SCREEN, log_path=tmp_path / "xvfb.log") as display:
        processes = [ManagedProcess(["rostopic", "pub", "-r", "2", topic, kind, message], env=master.env,
                                    log_path=tmp_path / f"pub{k}.log") for k, (topic, kind, message) in
                     enumerate(MARKER_TOPICS)]
        rviz = ManagedProcess(["rviz", "-d", str(config)], env=display.env(master.env),
                              log_path=tmp_path / "rviz.log")
        try:
            deadline = time.monotonic() + 60.0
            while time.monotonic() < deadline:
                time.sleep(2.0)
                assert rviz.running(), rviz.log_tail()
                rgb = read_png(display.screenshot(tmp_path / "markers.png"))
                view = analyse(rgb).view
                assert view is not None
                for name, (point, colour) in wanted.items():
                    cx, cy = map_to_pixel(view, scale, centre, *point)
                    patch = rgb[int(cy) - 40:int(cy) + 40, int(cx) - 90:int(cx) + 90]
                    found[name] = int(tinted(patch, colour).sum())
                if all(count >= 20 for count in found.values()):
                    break
        finally:
            rviz.stop()
            for proc in processes:
                proc.stop()
    log = (tmp_path / "rviz.log").read_text(errors="replace")
    assert all(count >= 20 for count in found.values()), f"pixels of each marker's colour where it is: {found}"
    assert rviz_errors(log) == [], rviz_errors(log)
