"""Compile flex_nav's numba kernels once, into numba's on-disk cache (``python -m flex_nav.nav.warm_cache``).

tools/install.sh runs it, so that the first planner or controller started after an install (often several
nodes at once) loads compiled code instead of each compiling it for seconds. Safe to run again: with a
warm cache it takes a fraction of a second.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from flex_nav.nav.control.controller import warm_up as warm_up_controller
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.costmap.costmap_grid import CostmapGeometry
from flex_nav.nav.costmap.inflation import InflationParams
from flex_nav.nav.costmap.layered import Costmap
from flex_nav.nav.costmap.obstacle_layer import LaserScan, ObstacleLayerParams
from flex_nav.nav.planning.planner import GridPlanner


def warm() -> float:
    """Run every compiled kernel on a tiny scene; returns the wall time it took [s]."""
    started = time.monotonic()
    costmap = Costmap(CostmapGeometry(40, 40, 0.05), obstacles=ObstacleLayerParams(),
                      inflation=InflationParams(0.1, 0.3, 3.0))
    costmap.add_scan(LaserScan(np.full(36, 1.0), -np.pi, np.pi / 18, 0.05, 5.0, 1.0, 1.0, 0.0))
    costmap.update()
    GridPlanner().plan(costmap.costs, costmap.geometry, (0.2, 0.2), (1.8, 1.8))
    warm_up_controller(PurePursuitParams())
    return time.monotonic() - started


if __name__ == "__main__":
    print(f"[flex_nav warm_cache] compiled kernels ready in {warm():.1f} s")
    sys.exit(0)
