"""Tracked people on the operator console's map, seen in a real browser (headless Debian Chromium and Selenium).

The stack of the push_or_avoid scenarios without the camera: the S6 world (an open room that four scripted people
walk across), one TurtleBot 4 with its navigation and behavior runner (oracle localization), its path controller
tracking moving obstacles in the scan (``pure_pursuit_path/yield_to_people``, as ``flex_nav.apps.scenario_run`` sets
it), and the console on 127.0.0.1. The robot stands at its start facing the walkers; nothing is driven. The page is the
only observer (this process starts no ROS node): the people the controller's tracker confirms must be drawn on the
map's canvas (its ``data-people`` list, and pixels of the people's colour where they are drawn) near the lines the
world's scripts walk them along. Then ``rosservice call`` asks the tracker to forget them
(``~people_tracker/forget``): it must say it forgot at least one, and people must be drawn again from the scans after.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import re
import time
from pathlib import Path
from typing import Any, Dict, List, Sequence, Tuple

import pytest
from harness import REPO_ROOT, run_command_bounded

from flex_nav.exceptions import NotReadyError
from flex_nav.testing.browser import HeadlessBrowser
from flex_nav.testing.private_master import free_port
from flex_nav.testing.process import ManagedProcess

WORLD = "s6_people_crossing"
ROBOT = "robot1"
RUNNER = f"/{ROBOT}/behavior_runner"
STARTUP_S = 180.0  # [s] wall bound of the stack's start, up to the map and the robot on the page
PEOPLE_S = 90.0  # [s] wall bound of the wait for tracked people on the page
FORGET_TIMEOUT_S = 30.0  # [s] wall bound of `rosservice call .../people_tracker/forget`
NEAR_WALK_M = 0.6  # [m] a person drawn this close to a walker's line counts as that walker
pytestmark = [pytest.mark.ros]


def _to_segment(point: Tuple[float, float], a: Sequence[float], b: Sequence[float]) -> float:
    ax, ay, bx, by = a[0], a[1], b[0], b[1]
    dx, dy = bx - ax, by - ay
    t = 0.0 if dx == dy == 0.0 else max(0.0, min(1.0, ((point[0] - ax) * dx + (point[1] - ay) * dy) /
                                                  (dx * dx + dy * dy)))
    return math.dist(point, (ax + t * dx, ay + t * dy))


def walk_distance(point: Tuple[float, float], walks: List[List[Tuple[float, float]]]) -> float:
    """[m] from ``point`` to the nearest line a walker walks along (each walker's polyline, closed)."""
    return min(_to_segment(point, a, b) for walk in walks for a, b in zip(walk, walk[1:] + walk[:1]))


def drawn_people(browser: HeadlessBrowser) -> List[Dict[str, Any]]:
    """The people the page drew, each with the colour of the canvas pixel at its centre (read in the same script
    as the list, so both belong to one drawing)."""
    found = browser.script(
        "const c = document.getElementById('map'); if (!c.dataset.view || !c.dataset.people) return [];"
        "const v = JSON.parse(c.dataset.view); const ctx = c.getContext('2d');"
        "return JSON.parse(c.dataset.people).map(([x, y]) => {"
        "  const cx = Math.round(v.left + (x - v.ox) * v.k); const cy = Math.round(v.bottom - (y - v.oy) * v.k);"
        "  const inside = cx >= 0 && cy >= 0 && cx < c.width && cy < c.height;"
        "  return {x, y, rgb: inside ? [...ctx.getImageData(cx, cy, 1, 1).data.slice(0, 3)] : null}; });")
    return list(found or [])


def people_coloured(rgb: Sequence[int] | None) -> bool:
    """The people's disc (orange, half transparent) or its heading line over whatever the map shows there: red
    well above green well above blue. The map's grey, white and black cells, the scan's red and the plans' blue and
    green are not."""
    return rgb is not None and rgb[0] > rgb[1] + 20 and rgb[1] > rgb[2] + 20


def test_the_tracked_people_are_drawn_where_the_walkers_walk(tmp_path: Path) -> None:
    from flex_nav.apps import nav_demo, scenario_run  # noqa: PLC0415
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    world = load_world(WORLD)
    walks = [[(float(x), float(y)) for x, y in person.waypoints] for person in world.people]
    assert len(walks) == 4 and all(len(walk) >= 2 for walk in walks), "S6 should have four walking people"
    run = nav_demo.RobotRun(ROBOT, scenario_run.PROFILE, [("goal", world.goals["goal"])])
    run.pose = world.spawns[0].pose if world.spawns else world.goals["start"]
    # oracle localization (the simulator's map -> odom): with the localizer on a loaded machine its map -> odom came
    # 0.45-0.6 s after each scan, later than the tracker waits for it, and the tracker dropped every scan
    system = argparse.Namespace(world=WORLD, rtf=1.0, seed=0, gui=False, autonomy="full", behavior="push_or_avoid",
                                localization="oracle", map=None)
    params = {f"/{ROBOT}/pure_pursuit_path/yield_to_people": True}  # the tracker publishes ~people while watched
    port = free_port()
    with contextlib.ExitStack() as exits:
        processes, env = nav_demo.start_system(exits, system, [run], tmp_path, params=params, bag=False)
        console = ManagedProcess(["rosrun", "flex_nav", "console", "_host:=127.0.0.1", f"_port:={port}",
                                  "_discovery_period_s:=0.5"], env=env, log_path=tmp_path / "logs" / "console.log")
        exits.callback(console.stop)
        browser = exits.enter_context(HeadlessBrowser())

        def wait(probe: Any, what: str, timeout_s: float) -> Any:
            try:
                return browser.wait_for(probe, what, timeout_s)
            except NotReadyError as err:
                dead = [p.log_path for p in [*processes, console] if not p.running()]
                pytest.fail(f"{err}; exited: {dead}; logs in {tmp_path / 'logs'}")

        def page_up() -> bool:
            from selenium.common.exceptions import WebDriverException  # noqa: PLC0415

            try:
                browser.driver.get(f"http://127.0.0.1:{port}/")
            except WebDriverException:  # connection refused: the console is not listening yet
                return False
            return bool(browser.script("return !!document.getElementById('map')"))

        wait(page_up, "the console's page", STARTUP_S)
        started = time.monotonic()

        def robot_on_the_map() -> bool:
            drawn = browser.script("return document.getElementById('map').dataset.drawn || '{}'")
            return "pose" in json.loads(drawn).get(RUNNER, {})

        wait(robot_on_the_map, "the map and the robot drawn", STARTUP_S)
        people = wait(lambda: [p for p in drawn_people(browser) if people_coloured(p["rgb"])] or None,
                      "tracked people drawn on the map", PEOPLE_S)
        seen_s = time.monotonic() - started
        near = [p for p in people if walk_distance((p["x"], p["y"]), walks) < NEAR_WALK_M]
        assert near and len(near) >= len(people) - 1, f"people drawn off the walkers' lines: {people} (lines {walks})"
        counts = json.loads(browser.script("return document.getElementById('map').dataset.drawn"))[RUNNER]
        assert counts.get("people", [0])[0] >= 1, counts
        print(f"people drawn {seen_s:.1f} s after the robot: {people}", flush=True)

        # the operator's way to make the tracker start afresh (scenario_run calls it where a world's script starts):
        # Debian's rosservice (the system python) finds flex_nav's service types once the venv is activated
        forget = run_command_bounded(
            ["bash", "-c", f"source {REPO_ROOT / '.venv' / 'bin' / 'activate'} && rosservice call "
                           f"/{ROBOT}/pure_pursuit_path/people_tracker/forget '{{before: {{secs: 0, nsecs: 0}}}}'"],
            env, FORGET_TIMEOUT_S)
        assert forget.returncode == 0 and "ok: True" in forget.output, forget.output
        forgotten = re.search(r"forgot (\d+) tracks", forget.output)
        assert forgotten and int(forgotten.group(1)) >= 1, forget.output
        again = wait(lambda: [p for p in drawn_people(browser) if people_coloured(p["rgb"])] or None,
                     "tracked people drawn again after the tracker forgot them", PEOPLE_S)
        assert any(walk_distance((p["x"], p["y"]), walks) < NEAR_WALK_M for p in again), again
