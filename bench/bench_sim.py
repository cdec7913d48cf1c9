#!/usr/bin/env python3
"""Simulator benchmark: real-time factor (RTF) of a TurtleBot 2 in the lab obstacle course.

Robot: the ``kobuki`` profile with a 360-beam lidar (1 deg, full circle) at 10 Hz, odometry at 50 Hz,
bumpers at 50 Hz, physics at 240 Hz, driving a reactive wander (turn away when the scan shows
something within 0.5 m ahead) for ``SIM_SECONDS`` of simulated time. The reference, measured in the
same run, is real time: 1.0x. RTF = simulated time / wall time.

1. core: :class:`flex_nav_sim.simulation.Simulation` alone (no ROS), camera off; for information.
2. node: ``rosrun flex_nav sim`` at ``_rtf:=0`` against a private roscore, with a listener process
   subscribed to every topic the node publishes (so every message is serialised and sent) and
   driving the robot from the scans; camera off. Target >= 5x.
3. node as in 2 with the RGB-D camera (320x240 colour + 32FC1 depth) at 5 Hz. Target >= 3x.

Each run prints the cost split: physics, rays (lidar), camera, other sensors and ROS publishing.
Exit status 1 if a target is missed.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Dict, Sequence, Tuple, Union

import yaml

if TYPE_CHECKING:
    import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

SIM_SECONDS = 60.0  # [s] simulated time per run
WORLD = "lab"
SPAWN = (1.0, 1.0, 0.0)  # [m, m, deg]
TARGET_NO_CAMERA = 5.0  # [x real time]
TARGET_CAMERA = 3.0
NODE_TIMEOUT_S = 300.0  # [s] wall-time bound on one node run
STATS = re.compile(
    r"t = (?P<t>[\d.]+) s in (?P<wall>[\d.]+) s wall, real-time factor (?P<rtf>[\d.]+); "
    r"cost: physics (?P<physics>[\d.]+) s, lidar (?P<lidar>[\d.]+) s, camera (?P<camera>[\d.]+) s, "
    r"other_sensors (?P<other>[\d.]+) s, ros_publishing (?P<ros>[\d.]+) s"
)


def bench_profile(folder: Path, camera: bool) -> Path:
    """The kobuki profile with a 360-beam 10 Hz lidar (and the camera at 5 Hz, or none)."""
    data = yaml.safe_load((REPO / "sim" / "robots" / "kobuki.yaml").read_text())
    data["name"] = "kobuki_bench"
    data["lidar"].update(angle_min_deg=-180.0, angle_max_deg=179.0, angle_increment_deg=1.0, rate=10.0)
    data["odometry"]["rate"] = 50.0
    data["bumper"]["rate"] = 50.0
    if camera:
        data["camera"]["rate"] = 5.0
    else:
        data["camera"] = None
    path = folder / ("kobuki_bench_camera.yaml" if camera else "kobuki_bench.yaml")
    path.write_text(yaml.safe_dump(data))
    return path


def wander(
    ranges: Union[np.ndarray, Sequence[float]], angle_min: float, increment: float, t: float
) -> Tuple[float, float]:
    """(v [m/s], w [rad/s]): forward with a slow weave; turn in place when blocked within 0.5 m ahead."""
    n = len(ranges)
    ahead = [ranges[i] for i in range(n) if abs(angle_min + i * increment) < math.radians(35.0)]
    if ahead and min(ahead) < 0.5:
        return 0.0, 1.2
    return 0.45, 0.4 * math.sin(t / 3.0)


def run_core() -> dict:
    from flex_nav_sim.profiles import load_profile  # noqa: PLC0415
    from flex_nav_sim.readings import ScanReading  # noqa: PLC0415
    from flex_nav_sim.simulation import SensorOptions, Simulation  # noqa: PLC0415
    from flex_nav_sim.world import Spawn, load_world  # noqa: PLC0415

    with tempfile.TemporaryDirectory() as tmp:
        profile = load_profile(bench_profile(Path(tmp), camera=False))
    spawn = Spawn("robot1", "kobuki", (SPAWN[0], SPAWN[1], math.radians(SPAWN[2])))
    with Simulation(
        load_world(WORLD), [spawn], seed=1, profiles={"robot1": profile}, sensors=SensorOptions(camera=False)
    ) as sim:
        spec = profile.lidar
        start = time.perf_counter()
        while sim.time < SIM_SECONDS:
            for reading in sim.step():
                if isinstance(reading, ScanReading):
                    v, w = wander(reading.ranges, spec.angle_min, spec.angle_increment, sim.time)
                    sim.command("robot1", v, w)
        wall = time.perf_counter() - start
        costs = dict(sim.costs)
        return {
            "t": sim.time,
            "wall": wall,
            "rtf": sim.time / wall,
            "physics": costs["physics"],
            "lidar": costs["lidar"],
            "camera": costs["camera"],
            "other": costs["other_sensors"],
            "ros": 0.0,
        }


def run_node(camera: bool) -> dict:
    from flex_nav.testing.private_master import PrivateMaster  # noqa: PLC0415
    from flex_nav.testing.process import ManagedProcess  # noqa: PLC0415

    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        profile = bench_profile(tmp, camera)
        master = PrivateMaster(ros_home=tmp / "ros_home").start()
        listener = None
        try:
            env = dict(master.env)
            env["PATH"] = f"{REPO / '.venv' / 'bin'}:{env.get('PATH', '')}"
            listener = ManagedProcess(
                [sys.executable, str(Path(__file__).resolve()), "--listener", str(tmp / "received.txt")],
                env=env,
                log_path=tmp / "listener.log",
            )
            time.sleep(1.0)
            x, y, yaw = SPAWN
            sim = ManagedProcess(
                [
                    str(REPO / "scripts" / "sim"),
                    f"_world:={WORLD}",
                    f"_robots:=robot1:{profile}:{x}:{y}:{yaw}",
                    "_rtf:=0",
                    f"_duration:={SIM_SECONDS}",
                    f"_camera:={'true' if camera else 'false'}",
                    "_seed:=1",
                ],
                env=env,
                log_path=tmp / "sim.log",
            )
            try:
                sim.popen.wait(timeout=NODE_TIMEOUT_S)
            finally:
                sim.stop()
            log = (tmp / "sim.log").read_text(errors="replace")
            matches = list(STATS.finditer(log))
            if sim.popen.returncode != 0 or not matches:
                raise RuntimeError(f"sim node failed (exit {sim.popen.returncode}):\n{log[-3000:]}")
            time.sleep(0.6)  # the listener rewrites its counts every 0.5 s
            received = tmp / "received.txt"
            listened = received.read_text() if received.is_file() else ""
        finally:
            if listener is not None:
                listener.stop()
            master.stop()
    figures: Dict[str, Union[float, str]] = {k: float(v) for k, v in matches[-1].groupdict().items()}
    figures["listener"] = listened.strip().splitlines()[-1] if listened.strip() else "(no listener output)"
    return figures


def listener_main(out: Path) -> int:
    """Subscribe to every topic of robot1 (raw, no deserialisation) and drive it from its scans."""
    import rospy  # noqa: PLC0415
    from geometry_msgs.msg import Twist  # noqa: PLC0415
    from sensor_msgs.msg import LaserScan  # noqa: PLC0415

    from flex_nav.ros.node import init_node  # noqa: PLC0415

    init_node("bench_listener")
    counts: dict = {}
    topics = ["/clock", "/tf", "/tf_static", "/sim_events"] + [
        f"/robot1/{t}"
        for t in (
            "odom",
            "ground_truth",
            "events/bumper",
            "bumper_state",
            "sim_events",
            "camera/rgb/image_raw",
            "camera/rgb/camera_info",
            "camera/depth/image_raw",
            "camera/depth/camera_info",
        )
    ]

    def count(topic: str) -> Callable[[Any], None]:
        def callback(_msg: Any) -> None:
            counts[topic] = counts.get(topic, 0) + 1

        return callback

    subscribers = [rospy.Subscriber(t, rospy.AnyMsg, count(t), queue_size=100) for t in topics]
    cmd = rospy.Publisher("/robot1/cmd_vel", Twist, queue_size=1)

    def on_scan(scan: LaserScan) -> None:
        counts["/robot1/scan"] = counts.get("/robot1/scan", 0) + 1
        v, w = wander(scan.ranges, scan.angle_min, scan.angle_increment, scan.header.stamp.to_sec())
        msg = Twist()
        msg.linear.x, msg.angular.z = v, w
        cmd.publish(msg)

    subscribers.append(rospy.Subscriber("/robot1/scan", LaserScan, on_scan, queue_size=1))
    while not rospy.is_shutdown():  # the message counts, rewritten every 0.5 s (wall)
        time.sleep(0.5)
        out.write_text("received: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) + "\n")
    return 0


def report(name: str, f: dict, target: float) -> bool:
    wall = f["wall"]
    split = ", ".join(
        f"{label} {f[key]:.2f} s ({100.0 * f[key] / wall:.0f} %)"
        for label, key in (
            ("physics", "physics"),
            ("rays", "lidar"),
            ("camera", "camera"),
            ("other sensors", "other"),
            ("ROS publishing", "ros"),
        )
    )
    verdict = "" if target <= 0 else (" PASS" if f["rtf"] >= target else " FAIL")
    goal = f" (target >= {target:.0f}x)" if target > 0 else " (for information)"
    print(f"{name}: {f['t']:.0f} s simulated in {wall:.2f} s wall -> {f['rtf']:.2f}x real time{goal}{verdict}")
    print(f"    cost: {split}")
    if "listener" in f:
        print(f"    listener {f['listener']}")
    return target <= 0 or f["rtf"] >= target


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--listener", metavar="COUNTS_FILE", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.listener:
        return listener_main(Path(args.listener))
    print(
        f"bench_sim: kobuki (TurtleBot 2), world {WORLD}, 360-beam lidar 10 Hz, odometry 50 Hz, bumpers 50 Hz, "
        f"physics 240 Hz, {SIM_SECONDS:.0f} s simulated per run"
    )
    print("reference: real time = 1.00x (measured: wall clock of the same run)")
    ok = report("core, no ROS, no camera", run_core(), 0.0)
    ok &= report("node + ROS publishing, no camera", run_node(camera=False), TARGET_NO_CAMERA)
    ok &= report("node + ROS publishing, camera 320x240 at 5 Hz", run_node(camera=True), TARGET_CAMERA)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
