"""``python -m flex_nav.apps.rviz_screenshot OUT.png``: RViz with the project's config, on the running demo, as a
picture (the README's docs/images/rviz_demo.png is made so; test/test_rviz_system.py checks what it shows).

Starts the demo's stack (:func:`flex_nav.apps.nav_demo.start_system`: private master, simulator, map server, per
robot navigation and behavior runner; ``--robots`` 1..3), waits until every robot is localized and waits for a goal,
sends each robot its first goal of the lap, starts a virtual X display (Xvfb on a free display number) and ``rviz -d
rviz/flex_nav.rviz`` on it (``rviz/multi_robot.rviz`` for two or three robots; ``--config`` another), and takes a
picture of the screen (ImageMagick's ``import``) every ``--period`` seconds until every robot has driven at least
``--drive`` metres and stands at its goal and the 3D view shows the map, the costmaps, the scan and the green
footprint and plan (at most ``--timeout`` seconds), then writes the last picture to OUT.png. RViz's output is kept
in ``<work>/logs/rviz.log``. Everything started is stopped at the end. Exit status 0; 1 when the view never showed
everything (the picture is written anyway, the missing parts are printed); 2 when something could not start (e.g.
RViz not installed).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import re
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np

from flex_nav.exceptions import FlexNavError, NotReadyError
from flex_nav.testing.process import ManagedProcess
from flex_nav.testing.xvfb import VirtualDisplay, missing_tools

REPO_ROOT = Path(__file__).resolve().parents[3]
CONFIGS = {1: REPO_ROOT / "rviz" / "flex_nav.rviz", 2: REPO_ROOT / "rviz" / "multi_robot.rviz",
           3: REPO_ROOT / "rviz" / "multi_robot.rviz"}
SCREEN = (1400, 900)  # [px] the virtual screen: the configs' window size
READY_TIMEOUT_S = 90.0  # [s] wall: the stack localized and waiting for goals
VIEW_TIMEOUT_S = 120.0  # [s] wall: the robots driven and everything drawn after the goals were sent

# How RViz 1.14.19 draws the configs' displays (software OpenGL on Xvfb), as rules on a pixel's RGB: the global
# costmap (alpha 0.4) and the local one (alpha 0.5) lie over the map (alpha 0.7), and the blend of the three is
# not the same from one run to the next (lethal cells measured (110, 8, 110) in one, (40, 9, 40) in another), so
# the rules take colour families, not exact values.
BACKGROUND = (48, 48, 48)  # Global Options: Background Color (exact: it is what finds the 3D view)
MIN_SHARE = {"free": 0.10, "obstacle": 0.01, "inscribed": 0.005}  # share of the 3D view at least
MIN_COUNT = {"scan": 40, "green": 40}  # pixels at least
RING_M = (0.10, 0.30)  # [m] the annulus around a robot's pose where its footprint outline is looked for
RING_BINS = 36  # angular bins of the annulus
RVIZ_ERROR = re.compile(r"^\s*\[ *ERROR *\][^\n]*(?:\n(?!\s*\[)[^\n]*)*", re.MULTILINE)
ANSI = re.compile(r"\x1b\[[0-9;]*m")
# The one ERROR that Mesa's GLSL linker makes RViz 1.14 log for the Map display's palette shader: the map is drawn
# all the same (the screenshots show it); a GL driver message, not one about the config or its displays.
KNOWN_GL_ERROR = "indexed_8bit_image"


def colour_masks(rgb: np.ndarray) -> Dict[str, np.ndarray]:
    """Boolean masks of the displays' colour families in ``rgb`` (H x W x 3)."""
    r, g, b = (rgb[..., k].astype(np.int16) for k in range(3))
    grey = (np.abs(r - g) <= 6) & (np.abs(g - b) <= 6)
    return {
        "free": grey & (r >= 170) & (r <= 215),  # the map's free cells: white at alpha 0.7, no costmap over them
        "obstacle": (np.abs(r - b) <= 12) & (g <= 20) & (r >= 25),  # occupied: the costmaps' lethal purple
        "inscribed": (np.abs(g - b) <= 12) & (g >= 200) & (r <= g - 20),  # cells within the robot's radius: cyan
        "scan": (r >= 215) & (g <= 40) & (b <= 40),  # Scan: red points
        "green": (g >= r + 40) & (g >= b + 40) & (np.abs(r - b) <= 30),  # Footprint and Global plan: green lines
    }


@dataclass
class ViewReport:
    """What one screenshot shows: the 3D view's box in the picture and the pixels of each display's colour."""

    size: Tuple[int, int]  # (width, height) [px] of the picture
    view: Optional[Tuple[int, int, int, int]]  # (x0, y0, x1, y1) [px] the 3D view (background-coloured box)
    distinct_colours: int  # in the 3D view
    counts: Dict[str, int] = field(default_factory=dict)  # pixels of each colour family in the 3D view
    view_pixels: int = 0

    def share(self, name: str) -> float:
        return self.counts.get(name, 0) / self.view_pixels if self.view_pixels else 0.0

    def problems(self) -> List[str]:
        """What is missing from the view (empty: the map, costmaps, scan and green lines are drawn)."""
        if self.view is None:
            return ["no 3D view (no area of the background colour): RViz's window is not on the screen"]
        out = [f"{name}: {self.share(name):.2%} of the view (want >= {least:.1%})"
               for name, least in MIN_SHARE.items() if self.share(name) < least]
        out += [f"{name}: {self.counts.get(name, 0)} px (want >= {least})"
                for name, least in MIN_COUNT.items() if self.counts.get(name, 0) < least]
        if self.distinct_colours < 50:
            out.append(f"only {self.distinct_colours} distinct colours in the view")
        return out

    def line(self) -> str:
        shares = ", ".join(f"{name} {count} px ({self.share(name):.1%})" for name, count in self.counts.items())
        return f"3D view {self.view} of {self.size}, {self.distinct_colours} colours: {shares}"


def view_box(rgb: np.ndarray) -> Optional[Tuple[int, int, int, int]]:
    """(x0, y0, x1, y1) [px] of RViz's 3D view: the rows and columns holding many background-coloured pixels."""
    height, width = rgb.shape[:2]
    background = np.all(rgb == np.array(BACKGROUND, dtype=rgb.dtype), axis=2)
    rows = np.nonzero(background.sum(axis=1) > 0.1 * width)[0]
    cols = np.nonzero(background.sum(axis=0) > 0.1 * height)[0]
    if rows.size == 0 or cols.size == 0:
        return None
    return int(cols[0]), int(rows[0]), int(cols[-1]) + 1, int(rows[-1]) + 1


def analyse(rgb: np.ndarray) -> ViewReport:
    """The :class:`ViewReport` of an RViz screenshot (H x W x 3, uint8 RGB)."""
    height, width = rgb.shape[:2]
    box = view_box(rgb)
    if box is None:
        return ViewReport((width, height), None, 0)
    x0, y0, x1, y1 = box
    view = rgb[y0:y1, x0:x1]
    flat = view.reshape(-1, 3).astype(np.int32)
    codes = (flat[:, 0] << 16) | (flat[:, 1] << 8) | flat[:, 2]
    report = ViewReport((width, height), box, int(np.unique(codes).size), view_pixels=int(flat.shape[0]))
    report.counts = {name: int(mask.sum()) for name, mask in colour_masks(view).items()}
    return report


def map_to_pixel(view: Tuple[int, int, int, int], scale: float, centre: Tuple[float, float],
                 x: float, y: float) -> Tuple[float, float]:
    """[px] Where map point (``x``, ``y``) [m] is drawn in a top-down view ``view`` (x0, y0, x1, y1) [px] of
    ``scale`` [px/m] centred on ``centre`` [m] (RViz's TopDownOrtho: x right, y up)."""
    x0, y0, x1, y1 = view
    return ((x0 + x1) / 2.0 + (x - centre[0]) * scale, (y0 + y1) / 2.0 - (y - centre[1]) * scale)


def tinted(rgb: np.ndarray, colour: Tuple[int, int, int], min_chroma: float = 40.0, min_cosine: float = 0.95
           ) -> np.ndarray:
    """Mask of the pixels of ``rgb`` (H x W x 3) tinted by ``colour``, whatever grey it was blended over: their
    chroma (RGB minus its mean) points the way ``colour``'s does and is at least ``min_chroma`` long."""
    pixels = rgb.astype(np.float64)
    chroma = pixels - pixels.mean(axis=-1, keepdims=True)
    reference = np.array(colour, dtype=np.float64) - float(np.mean(colour))
    length = np.linalg.norm(chroma, axis=-1)
    cosine = (chroma @ reference) / np.maximum(length * float(np.linalg.norm(reference)), 1e-9)
    mask: np.ndarray = (length >= min_chroma) & (cosine >= min_cosine)
    return mask


def ring_coverage(rgb: np.ndarray, centre_px: Tuple[float, float], scale: float,
                  colour: Tuple[int, int, int] = (0, 255, 0)) -> float:
    """Share [0..1] of the angular bins of the annulus :data:`RING_M` around ``centre_px`` that hold a pixel
    tinted by ``colour``: ~1 for a footprint outline drawn there, small for a plan line passing through."""
    inner, outer = (radius * scale for radius in RING_M)
    cx, cy = centre_px
    left, top = max(0, int(cx - outer)), max(0, int(cy - outer))
    patch = rgb[top:int(cy + outer) + 1, left:int(cx + outer) + 1]
    if patch.size == 0:
        return 0.0
    ys, xs = np.nonzero(tinted(patch, colour))
    dx, dy = xs + left - cx, ys + top - cy
    radius = np.hypot(dx, dy)
    inside = (radius >= inner) & (radius <= outer)
    bins = ((np.arctan2(dy[inside], dx[inside]) + np.pi) / (2 * np.pi) * RING_BINS).astype(int) % RING_BINS
    return float(np.unique(bins).size) / RING_BINS


def footprint_colours(config: Path, robots: Sequence[str]) -> List[Tuple[int, int, int]]:
    """The colour of each robot's Footprint display in ``config`` (the display on ``/<robot>/footprint``)."""
    import yaml  # noqa: PLC0415

    def displays(items: List[Dict[str, object]]) -> Iterator[Dict[str, object]]:
        for item in items:
            inner = item.get("Displays")
            yield from displays(inner) if isinstance(inner, list) else [item]

    found = {str(d.get("Topic")): str(d.get("Color")) for d in
             displays(yaml.safe_load(config.read_text())["Visualization Manager"]["Displays"])}
    out = []
    for robot in robots:
        colour = found.get(f"/{robot}/footprint")
        if colour is None:
            raise NotReadyError(f"{config} has no footprint display for {robot}")
        red, green, blue = (int(part) for part in colour.split(";"))
        out.append((red, green, blue))
    return out


def read_png(path: Path) -> np.ndarray:
    """The picture at ``path`` as H x W x 3 uint8 RGB."""
    import cv2  # noqa: PLC0415 - only to read the screenshot

    image = cv2.imread(str(path), cv2.IMREAD_COLOR)
    if image is None:
        raise NotReadyError(f"{path}: not a readable picture")
    return np.ascontiguousarray(image[:, :, ::-1])


def rviz_errors(log_text: str) -> List[str]:
    """RViz's ERROR messages in its output (a message's continuation lines included), but Mesa's known
    :data:`KNOWN_GL_ERROR`."""
    return [m.strip() for m in RVIZ_ERROR.findall(ANSI.sub("", log_text)) if KNOWN_GL_ERROR not in m]


@dataclass
class Shot:
    """One RViz screenshot of the running demo and what came with it."""

    path: Path
    report: ViewReport
    rviz_log: str  # RViz's stdout and stderr up to the picture
    rviz_running: bool  # RViz was still running when the picture was taken
    driven_m: List[float]  # [m] each robot's distance driven when the picture was taken
    poses: List[Optional[Tuple[float, float, float]]]  # each robot's ground truth (x, y [m], yaw [rad]) then
    starts: List[Tuple[float, float]]  # [m] where each robot started
    view_scale: float  # [px/m] the config's top-down view
    view_centre: Tuple[float, float]  # [m] the point of the map at the view's centre
    footprint_colours: List[Tuple[int, int, int]]  # each robot's Footprint display colour in the config
    plans: List[int]  # global plans each robot had published
    waited_s: float  # [s] wall from RViz's start to the picture
    pictures: int  # screenshots taken until everything showed

    def summary(self) -> Dict[str, object]:
        """The shot's facts for ``--report`` (JSON)."""
        return {"path": str(self.path), "view": self.report.view, "counts": self.report.counts,
                "view_pixels": self.report.view_pixels, "distinct_colours": self.report.distinct_colours,
                "problems": self.report.problems(), "rviz_errors": rviz_errors(self.rviz_log),
                "rviz_running": self.rviz_running, "driven_m": self.driven_m, "plans": self.plans,
                "poses": self.poses, "starts": self.starts, "view_scale": self.view_scale,
                "view_centre": self.view_centre, "footprint_colours": self.footprint_colours,
                "waited_s": round(self.waited_s, 1), "pictures": self.pictures}


def view_geometry(config: Path) -> Tuple[float, Tuple[float, float]]:
    """The scale [px/m] and centre [m] of ``config``'s current view (a TopDownOrtho view)."""
    import yaml  # noqa: PLC0415

    current = yaml.safe_load(config.read_text())["Visualization Manager"]["Views"]["Current"]
    return float(current["Scale"]), (float(current["X"]), float(current["Y"]))


def checked_setup(config: Path) -> Path:
    """``config``, once RViz, Xvfb and ImageMagick's import are installed and ``config`` exists (else NotReadyError
    naming what is missing)."""
    missing = missing_tools("rviz", "Xvfb", "import")
    if missing:
        raise NotReadyError(f"{', '.join(missing)} not installed (Debian packages rviz, xvfb, imagemagick): "
                            "run tools/install.sh")
    if not config.is_file():
        raise NotReadyError(f"RViz config {config} not found")
    return config


def capture(out: Path, work: Path, *, robots: int = 1, config: Optional[Path] = None, drive_m: float = 0.8,
            period_s: float = 2.0, timeout_s: float = VIEW_TIMEOUT_S, rtf: float = 1.0) -> Shot:
    """Run the demo with ``robots`` robots and RViz with ``config`` under Xvfb; the screenshot at ``out``.

    ``work``: logs and the demo's output. Raises NotReadyError when something needed is missing or did not start;
    returns the last picture when the view never showed everything by ``timeout_s`` (its report says what)."""
    config = checked_setup(config or CONFIGS[robots])
    from flex_nav.apps import nav_demo  # noqa: PLC0415
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    args = nav_demo.parse_args(["--robots", str(robots), "--rtf", str(rtf), "--out", str(work)])
    runs = nav_demo.plan_robots(load_world(args.world), args.profile_list, 1)
    starts = [(run.pose[0], run.pose[1]) if run.pose else (0.0, 0.0) for run in runs]
    scale, centre = view_geometry(config)
    colours = footprint_colours(config, [run.name for run in runs])
    logs = work / "logs"
    with contextlib.ExitStack() as exits:
        processes, env = nav_demo.start_system(exits, args, runs, work, bag=False)
        import rospy  # noqa: PLC0415 - only once the master is up

        from flex_nav.ros.node import init_node  # noqa: PLC0415

        init_node("rviz_screenshot", anonymous=True)
        exits.callback(rospy.signal_shutdown, "the RViz screenshot is taken")
        monitor = nav_demo.DemoMonitor(runs)
        problem = nav_demo.wait_until_ready(monitor, processes, READY_TIMEOUT_S)
        if problem is not None:
            raise NotReadyError(f"the demo's stack did not start: {problem}; logs in {logs}")
        monitor.send_due_goals()
        display = exits.enter_context(VirtualDisplay(*SCREEN, log_path=logs / "xvfb.log"))
        rviz_log = logs / "rviz.log"
        rviz = ManagedProcess(["rviz", "-d", str(config)], env=display.env(env), log_path=rviz_log)
        exits.callback(rviz.stop, 5.0)
        started = time.monotonic()
        pictures = 0
        frame = work / "rviz_frame.png"
        while True:
            time.sleep(period_s)
            if not rviz.running():
                raise NotReadyError(f"rviz exited ({rviz.popen.returncode}): {rviz.log_tail(1500)}")
            dead = [p for p in processes if not p.running()]
            if dead:
                raise NotReadyError(f"{' '.join(dead[0].argv[:4])} exited (log {dead[0].log_path})")
            display.screenshot(frame)
            pictures += 1
            report = analyse(read_png(frame))
            with monitor.lock:
                driven = [run.distance_m for run in runs]
                plans = [len(run.plans) for run in runs]
                poses = [run.pose for run in runs]
                arrived = all(run.completed >= 1 for run in runs)
            waited = time.monotonic() - started
            if (arrived and min(driven) >= drive_m and not report.problems()) or waited > timeout_s:
                break
        out.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(frame, out)
        shot = Shot(out, report, rviz_log.read_text(errors="replace"), rviz.running(), driven, poses, starts, scale,
                    centre, colours, plans, waited, pictures)
        monitor.stopping = True
    return shot


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m flex_nav.apps.rviz_screenshot", description=__doc__)
    parser.add_argument("out", type=Path, help="the PNG to write")
    parser.add_argument("--robots", type=int, default=1, choices=(1, 2, 3), help="robots (default %(default)s)")
    parser.add_argument("--config", type=Path, default=None,
                        help="RViz config (default rviz/flex_nav.rviz, rviz/multi_robot.rviz for 2 or 3 robots)")
    parser.add_argument("--drive", type=float, default=0.8, help="[m] distance each robot drives first")
    parser.add_argument("--timeout", type=float, default=VIEW_TIMEOUT_S, help="[s] bound of the wait for the view")
    parser.add_argument("--period", type=float, default=2.0, help="[s] between screenshots while waiting")
    parser.add_argument("--work", type=Path, default=None, help="logs and the demo's output (default: a temp dir)")
    parser.add_argument("--report", type=Path, default=None, help="also write what the picture shows here (JSON)")
    args = parser.parse_args(argv)
    work = args.work or Path(tempfile.mkdtemp(prefix="rviz_screenshot-"))
    try:
        shot = capture(args.out, work, robots=args.robots, config=args.config, drive_m=args.drive,
                       period_s=args.period, timeout_s=args.timeout)
    except FlexNavError as err:
        print(f"rviz_screenshot: {err}", file=sys.stderr)
        return 2
    print(f"rviz_screenshot: {shot.path} after {shot.waited_s:.1f} s ({shot.pictures} pictures); driven "
          f"{', '.join(f'{d:.1f}' for d in shot.driven_m)} m; {shot.report.line()}; logs in {work / 'logs'}")
    if args.report is not None:
        args.report.write_text(json.dumps(shot.summary(), indent=1))
    errors = rviz_errors(shot.rviz_log)
    for line in errors:
        print(f"rviz: {line}", file=sys.stderr)
    problems = shot.report.problems()
    if problems or errors or not shot.rviz_running:
        print(f"rviz_screenshot: the view is incomplete: {'; '.join(problems) or 'rviz errors'}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
