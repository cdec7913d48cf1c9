"""ReplanState: move_base's global replanning as a state — plan to the goal every period and publish the plan."""

from __future__ import annotations

from typing import Any, Optional

from actionlib_msgs.msg import GoalStatus
from nav_msgs.msg import Path
from std_msgs.msg import Header

from flex_nav.action_types import action_type
from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.msg import GetPathGoal, GetPathResult
from flex_nav_states import validation
from flex_nav_states.action_base import SERVER_LOST_S, ServerLossWatch
from flex_nav_states.backoff_state import retry_delay_s
from flex_nav_states.messages import to_stamp
from flex_nav_states.proxy_types import ActionClientLike, PublisherLike, proxies_of

GET_PATH = action_type("GetPath")


class ReplanState(State):
    """Plans to the goal with a GetPath server every period and publishes each new plan on a topic.

    Runs beside a FollowTopic controller (which follows ``plan_topic``) in a concurrency container, as
    move_base's planner thread replans at ``planner_frequency``. It never finishes by itself while plans
    keep coming; it fails after ``max_failures`` planning failures in a row or when the server is missing.
    A plan request without an answer for ``plan_timeout_s`` is cancelled and counts as a failure; a server that
    disconnects while a request is out fails the state after ``SERVER_LOST_S`` (as every action state). After a
    failed plan the next one starts later, doubling the period after each failure in a row up to
    ``backoff_max_s`` (a transient fault is not answered by back-to-back requests that all fail).

    -- action_name       str    GetPath server name, relative to the behavior's namespace.
    -- plan_topic        str    nav_msgs/Path topic the plans are published on (latched), each stamped at its
                                publication (the tick its answer was taken in; the planner stamped it at the
                                request): a controller that takes a Path only at a step after its stamp then
                                takes each plan at the same step whatever the load.
    -- period_s          float  [s] Time between the starts of two plans (> 0; move_base: 1 / planner_frequency).
    -- max_failures      int    Planning failures in a row before giving up (>= 1).
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- plan_timeout_s    float  [s] A plan request unanswered this long is cancelled and counts as a failure.
    -- backoff_max_s     float  [s] Longest time between the starts of two plans after failures (never below
                                period_s).

    ># goal  PoseStamped  The goal to plan to.
    #> plan  Path         The newest plan.

    <= failed  Planning failed max_failures times in a row, or the server is missing; the reason is logged.
    """

    def __init__(self, action_name: str = "get_path_server", plan_topic: str = "replan/plan", period_s: float = 1.0,
                 max_failures: int = 3, server_timeout_s: float = 5.0, *, plan_timeout_s: float = 5.0,
                 backoff_max_s: float = 4.0) -> None:
        super().__init__(outcomes=["failed"], input_keys=["goal"], output_keys=["plan"])
        owner = type(self).__name__
        self._action_name = validation.name(owner, "action_name", action_name)
        self._plan_topic = validation.name(owner, "plan_topic", plan_topic)
        self._replan_period_s = validation.number(owner, "period_s", period_s, positive=True, unit="[s]")
        self._max_failures = int(validation.number(owner, "max_failures", max_failures, minimum=1.0))
        self._server_timeout_s = validation.number(owner, "server_timeout_s", server_timeout_s, positive=True,
                                                   unit="[s]")
        self._plan_timeout_s = validation.number(owner, "plan_timeout_s", plan_timeout_s, positive=True, unit="[s]")
        self._backoff_max_s = max(self._replan_period_s,
                                  validation.number(owner, "backoff_max_s", backoff_max_s, positive=True, unit="[s]"))
        self._client: Optional[ActionClientLike] = None
        self._publisher: Optional[PublisherLike] = None
        self._goal: Any = None
        self._entered_s = 0.0
        self._next_plan_s = 0.0  # [s] when the next plan may start
        self._plan_in_flight = False  # a GetPath goal is out
        self._sent_s = 0.0  # [s] when it was sent
        self._server_loss = ServerLossWatch()  # the server disconnected while a request is out
        self._failures = 0
        self._plans = 0

    def on_start(self) -> None:
        proxies = proxies_of(self)
        self._client = proxies.action_client(self._action_name, GET_PATH.action)
        self._publisher = proxies.publisher(self._plan_topic, Path, latch=True)

    def on_enter(self, userdata: UserDataView) -> None:
        self._goal = GetPathGoal(pose=unwrap(userdata.goal))
        self._entered_s = self._next_plan_s = self.now_s()
        self._plan_in_flight = False
        self._failures = self._plans = 0

    def execute(self, userdata: UserDataView) -> Optional[str]:
        assert self._client is not None and self._publisher is not None
        now = self.now_s()
        if self._plan_in_flight:
            if not self._client.has_result():
                return self._unanswered(now)
            self._plan_in_flight = False
            result = self._client.result()
            if self._client.state() == GoalStatus.SUCCEEDED and result is not None and \
                    result.code == GetPathResult.SUCCESS and len(result.plan.poses) > 0:
                self._failures = 0
                self._plans += 1
                userdata.plan = result.plan
                self._publisher.publish(published_now(result.plan, now))
            elif self._failed(result.message if result is not None else "no result"):
                return "failed"
        if now < self._next_plan_s:
            return None
        if not self._client.is_available(0.0):
            if now - self._entered_s >= self._server_timeout_s:
                self.log_error(f"{self._action_name}: GetPath server not available after {self._server_timeout_s} s")
                return "failed"
            return None
        self._client.send_goal(self._goal, server_timeout_s=0.05)
        self._plan_in_flight = True
        self._sent_s = now
        self._server_loss.reset()
        self._next_plan_s = now + self._replan_period_s
        return None

    def _unanswered(self, now: float) -> Optional[str]:
        """The request out has no answer yet: "failed" when its server has gone, else None (wait, or count a
        request unanswered for plan_timeout_s as a failure and plan again at the next period)."""
        assert self._client is not None
        if self._server_loss.gone(self._client, now):
            self._client.cancel()
            self._plan_in_flight = False
            self.log_error(f"{self._action_name}: GetPath server went away during a plan "
                           f"(disconnected for {SERVER_LOST_S:g} s; request cancelled)")
            return "failed"
        if now - self._sent_s >= self._plan_timeout_s:
            self._client.cancel()
            self._plan_in_flight = False
            if self._failed(f"no answer within plan_timeout_s {self._plan_timeout_s:g} s; request cancelled"):
                return "failed"
        return None

    def _failed(self, reason: str) -> bool:
        """Count one failed plan with its reason (the next one waits the back-off); True when max_failures in a row
        have failed."""
        self._failures += 1
        self._next_plan_s = max(self._next_plan_s, self._sent_s + retry_delay_s(
            self._failures, self._replan_period_s, self._backoff_max_s))
        self.log_warn(f"{self._action_name}: replan {self._failures}/{self._max_failures} failed: {reason}")
        if self._failures >= self._max_failures:
            self.log_error(f"{self._action_name}: {self._failures} plans in a row failed; giving up")
            return True
        return False

    def on_exit(self, userdata: UserDataView) -> None:
        if self._plan_in_flight and self._client is not None and self._client.is_active():
            self._client.cancel()
        self._plan_in_flight = False


def published_now(plan: Path, now_s: float) -> Path:
    """``plan`` (its poses shared, not copied) with its header stamped ``now_s`` [s], the time it is published."""
    header = Header(seq=plan.header.seq, stamp=to_stamp(now_s), frame_id=plan.header.frame_id)
    return Path(header=header, poses=plan.poses)
