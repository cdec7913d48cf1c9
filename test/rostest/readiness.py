"""Readiness probes shared by rostest nodes (imported from this directory, not a test itself)."""

import time
from typing import Callable

from actionlib_msgs.msg import GoalStatus


def poll_until(predicate: Callable[[], object], timeout_s: float, period_s: float = 0.01) -> bool:
    """True once ``predicate()`` holds, asked every ``period_s`` [s]; False if it did not within ``timeout_s`` [s]."""
    deadline = time.monotonic() + timeout_s
    while not predicate():
        if time.monotonic() > deadline:
            return False
        time.sleep(period_s)
    return True


def connected(*endpoints, timeout_s):
    """Bounded wait until each publisher / subscriber has a connection: a message sent on an unlatched topic before
    that is lost. AssertionError naming the endpoints still unconnected after ``timeout_s`` [s]."""
    if not poll_until(lambda: all(e.get_num_connections() > 0 for e in endpoints), timeout_s, period_s=0.02):
        missing = [e.resolved_name for e in endpoints if e.get_num_connections() == 0]
        raise AssertionError(f"no connection within {timeout_s} s on {missing}")


def wait_until_active(client, timeout_s):
    """Bounded wait until the server has accepted ``client``'s goal (an ActionClientProxy); a cancel sent before
    that recalls the goal instead of preempting it."""
    deadline = time.monotonic() + timeout_s
    while client.state() != GoalStatus.ACTIVE and time.monotonic() < deadline:
        time.sleep(0.01)
    if client.state() != GoalStatus.ACTIVE:
        raise AssertionError(f"the goal did not become ACTIVE within {timeout_s} s (state {client.state()})")


def wait_until_goal_succeeds(client, goal, what, timeout_s, result_wait_s=10.0):
    """Send ``goal`` through ``client`` (an ActionClientProxy) until it SUCCEEDS, for at most ``timeout_s`` [s]:
    a planner answers only once it has the latched map and the robot's tf. AssertionError naming ``what`` and
    the last answer if it never does."""
    deadline = time.monotonic() + timeout_s
    answer = "no answer"
    while time.monotonic() < deadline:
        client.send_goal(goal)
        if client.wait_for_result(result_wait_s):
            if client.state() == GoalStatus.SUCCEEDED:
                return
            answer = client.result().message if client.result() is not None else f"state {client.state()}"
        time.sleep(0.1)
    raise AssertionError(f"{what} did not succeed within {timeout_s} s (map or robot tf missing?); "
                         f"last answer: {answer}")
