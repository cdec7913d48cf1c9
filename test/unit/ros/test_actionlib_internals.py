"""SimpleServerInternals on an unstarted SimpleActionServer (no master): the goal hook runs ahead of
SimpleActionServer's handler, ``locked`` holds both locks, a remembered goal's stamp and forgetting it, the
sender and status connections when there are none; GoalServer.finish refuses what is not a GoalOutcome.
The behaviour built on them is tested against a real master (goal_server.test, controller_safety.test,
clock_faults.test)."""

import threading

import actionlib
import pytest
import rospy
from actionlib_msgs.msg import GoalID

from flex_nav.action_types import action_type
from flex_nav.msg import FollowPathAction, FollowPathActionGoal
from flex_nav.ros.actionlib_internals import RememberedGoal, SimpleServerInternals
from flex_nav.ros.goal_server import GoalOutcome, GoalServer, GoalTicket


def unstarted_server() -> actionlib.SimpleActionServer:
    return actionlib.SimpleActionServer("unit_internals", FollowPathAction, auto_start=False)


def test_nothing_remembered_sent_or_connected_before_start():
    internals = SimpleServerInternals(unstarted_server())
    assert [internals.remembered_stamp(which) for which in RememberedGoal] == [None, None]
    assert internals.sender_of_current_goal() == ""
    assert internals.status_connections() == []


def test_the_hook_runs_before_simple_action_servers_own_goal_callback():
    server = unstarted_server()
    calls = []
    server.internal_goal_callback = lambda handle: calls.append(("simple", handle))
    SimpleServerInternals(server).intercept_goals(lambda handle: calls.append(("before", handle)))
    server.action_server.goal_callback("handle")
    assert calls == [("before", "handle"), ("simple", "handle")]


def test_locked_holds_both_locks_and_releases_them():
    server = unstarted_server()
    internals = SimpleServerInternals(server)

    def free_elsewhere() -> list:
        taken = []

        def probe() -> None:
            for lock in (server.action_server.lock, server.lock):
                got = lock.acquire(blocking=False)
                taken.append(got)
                if got:
                    lock.release()

        thread = threading.Thread(target=probe)
        thread.start()
        thread.join()
        return taken

    with internals.locked():
        assert free_elsewhere() == [False, False]
        with internals.locked():  # re-entrant, as inside actionlib's goal callback
            pass
    assert free_elsewhere() == [True, True]


def test_a_remembered_goal_has_its_stamp_until_forgotten():
    server = unstarted_server()
    internals = SimpleServerInternals(server)
    stamp = rospy.Time(42, 5)
    goal = FollowPathActionGoal(goal_id=GoalID(stamp=stamp, id="g1"))
    goal._connection_header = {"callerid": "/runner"}
    tracker = actionlib.status_tracker.StatusTracker(None, None, goal)
    server.current_goal = actionlib.ServerGoalHandle(tracker, server.action_server, None)
    assert internals.remembered_stamp(RememberedGoal.CURRENT) == stamp
    assert internals.remembered_stamp(RememberedGoal.NEXT) is None
    assert internals.sender_of_current_goal() == "/runner"
    internals.forget(RememberedGoal.CURRENT)
    assert internals.remembered_stamp(RememberedGoal.CURRENT) is None
    assert internals.sender_of_current_goal() == ""


def test_finish_refuses_an_outcome_that_is_not_a_goal_outcome():
    server = GoalServer("unit_finish", action_type("FollowPath"), lambda _ticket: None)
    ticket = GoalTicket(None, 1)
    server._current = ticket
    server.server.is_active = lambda: True
    with pytest.raises(ValueError, match=r"valid: GoalOutcome.SUCCEEDED, GoalOutcome.ABORTED"):
        server.finish(ticket, "succeeded", server.result("SUCCESS", "done"))  # type: ignore[arg-type]  # on purpose
    assert not server.finish(GoalTicket(None, 2), GoalOutcome.SUCCEEDED, server.result("SUCCESS", "done"))

