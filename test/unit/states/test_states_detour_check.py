"""DetourCheckState and detour_m: after a push, the plan through the pushed object is kept once when the replan is
a long detour (issue 28's h4)."""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import pytest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from unit.states.states_testlib import Harness

from flex_nav.exceptions import ConfigError
from flex_nav.nav.path import detour_m
from flex_nav_states.detour_check_state import DetourCheckState

THROUGH = [(1.0, 0.6), (9.0, 0.6)]  # the short route, through the box
AROUND = [(5.0, 0.6), (3.0, 0.6), (3.0, 6.0), (7.5, 6.0), (7.5, 0.6), (9.0, 0.6)]  # round the block: 18.8 m
BESIDE = [(5.0, 0.6), (6.0, 1.0), (7.0, 1.0), (9.0, 0.6)]  # past the pushed box within the route


def path_of(points: Sequence[Tuple[float, float]]) -> Path:
    path = Path()
    for x, y in points:
        pose = PoseStamped()
        pose.pose.position.x, pose.pose.position.y = x, y
        path.poses.append(pose)
    return path


def xy(points: List[Tuple[float, float]]) -> np.ndarray:
    return np.array(points, dtype=np.float64)


def test_detour_m_is_the_replan_less_the_rest_of_the_old_plan() -> None:
    assert detour_m(xy(THROUGH), xy(AROUND)) == pytest.approx(18.8 - 4.0)
    assert detour_m(xy(THROUGH), xy(BESIDE)) == pytest.approx(
        np.hypot(1.0, 0.4) + 1.0 + np.hypot(2.0, 0.4) - 4.0)
    assert detour_m(xy(THROUGH), xy([(9.0, 0.6)])) == pytest.approx(0.0)  # at the goal
    with pytest.raises(ConfigError, match="two paths with points"):
        detour_m(xy(THROUGH), np.zeros((0, 2)))


def check(state: DetourCheckState, plan: object, new_plan: Path,
          keeps: float = 0.0) -> Tuple[Optional[str], Dict[str, Any], str]:
    h = Harness(state, inputs={"plan": plan, "new_plan": new_plan, "keeps": keeps})
    result = h.start().run(1.0)
    return result.outcome, result.outputs, h.log_text()


def test_a_long_detour_keeps_the_old_plan_once() -> None:
    outcome, outputs, log = check(DetourCheckState(max_extra_m=3.0), path_of(THROUGH), path_of(AROUND))
    assert outcome == "keep"
    assert outputs["keeps"] == 1.0
    assert [(p.pose.position.x, p.pose.position.y) for p in outputs["plan"].poses] == THROUGH
    assert "14.8 m longer" in log
    outcome, outputs, log = check(DetourCheckState(max_extra_m=3.0), path_of(THROUGH), path_of(AROUND), keeps=1.0)
    assert outcome == "replanned" and outputs["plan"].poses[0].pose.position.y == 0.6
    assert len(outputs["plan"].poses) == len(AROUND)
    assert "kept 1 times for this goal already" in log


def test_a_short_replan_or_no_old_plan_is_taken() -> None:
    outcome, outputs, _ = check(DetourCheckState(max_extra_m=3.0), path_of(THROUGH), path_of(BESIDE))
    assert outcome == "replanned" and len(outputs["plan"].poses) == len(BESIDE)
    assert check(DetourCheckState(), None, path_of(AROUND))[0] == "replanned"
    assert check(DetourCheckState(), path_of([]), path_of(AROUND))[0] == "replanned"
    assert check(DetourCheckState(max_keeps=0), path_of(THROUGH), path_of(AROUND))[0] == "replanned"


@pytest.mark.parametrize("kwargs, match", [({"max_extra_m": 0.0}, "max_extra_m"), ({"max_keeps": -1}, "max_keeps"),
                                           ({"max_keeps": 1.5}, "max_keeps")])
def test_bad_parameters_are_refused_when_built(kwargs: dict, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        DetourCheckState(**kwargs)
