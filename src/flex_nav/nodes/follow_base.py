"""What the nodes serving FollowPath or FollowTopic share (``follow_*_server``, ``pure_pursuit_*``).

A FollowPath goal carries the path; a FollowTopic goal names a topic whose newest nav_msgs/Path is followed: an
illegal name (empty, ``..``, blanks) aborts the goal at once, and the first Path must come within
``~topic_timeout`` [s] (:class:`flex_nav.ros.topic_path.TopicPaths`; one stamped before the goal's
``newer_than``, or its start, only if no newer one comes). A goal ends with a result code (SUCCESS or FAILURE),
the reason and the robot's pose (NaN when unknown); feedback is FollowPathFeedback (pose, twist) or
FollowTopicFeedback (pose, the Path followed now). Which action a node serves is its :class:`GoalSource`.
"""

from __future__ import annotations

import abc
import enum
import math
import threading
from dataclasses import dataclass
from typing import Any, Callable, Optional, Sequence, Tuple

import rospy
from nav_msgs.msg import Path

from flex_nav.action_types import ActionType, action_type
from flex_nav.exceptions import ConfigError
from flex_nav.msg import FollowPathFeedback, FollowTopicFeedback
from flex_nav.nav.control.topic_name import topic_name_problem
from flex_nav.nav.planar import Pose2D
from flex_nav.ros.conversions import pose_of_xy_yaw
from flex_nav.ros.goal_server import GoalOutcome, GoalServer, GoalTicket
from flex_nav.ros.params import param_float, reject_unknown
from flex_nav.ros.private_ns import private_namespace
from flex_nav.ros.ros_clock import RosClock
from flex_nav.ros.topic_path import TopicPath, TopicPaths, fresh_from


class GoalSource(enum.Enum):
    """Where a node's goals take their path from (chosen by the node's script)."""

    PATH = "path"  # FollowPath: the path is in the goal
    TOPIC = "topic"  # FollowTopic: the newest Path on the topic named in the goal

    @property
    def action(self) -> str:
        """The action served."""
        return "FollowPath" if self is GoalSource.PATH else "FollowTopic"


@dataclass(frozen=True)
class GoalPath:
    """A goal's first path: the goal's own (``topic`` None), or the newest on the goal's topic when the goal
    began, taken as the ``count``-th Path that arrived there."""

    msg: Path
    topic: Optional[TopicPath]
    count: int = 0


def bad_path(topic: Optional[TopicPath], err: Exception) -> str:
    """The reason a goal ends when its path cannot be used (the goal's, or one that came on ``topic``)."""
    return f"bad path on {topic.topic}: {err}" if topic is not None else f"bad path: {err}"


class FollowNode(abc.ABC):
    """Base of a node serving FollowPath (:attr:`GoalSource.PATH`) or FollowTopic (:attr:`GoalSource.TOPIC`).

    The constructor validates the source and the node's private parameter names. The subclass's constructor
    then sets ``clock``, ``topic_timeout_s`` [s] and ``_topics`` (on ``_wake``), and calls :meth:`_serve` last.
    Each goal runs :meth:`_pursue` with the goal's first path once :meth:`_first_path` has it.
    """

    clock: RosClock
    topic_timeout_s: float  # [s] ROS time: FollowTopic's wait for the first Path
    _topics: TopicPaths
    server: GoalServer

    def __init__(self, source: GoalSource, parameters: Sequence[str]) -> None:
        if not isinstance(source, GoalSource):  # a caller without type checking
            valid = ", ".join(str(member) for member in GoalSource)  # type: ignore[unreachable]
            raise ConfigError(f"{type(self).__name__} source {source!r} is not valid (valid: {valid})")
        self.source = source
        self.name = private_namespace()
        reject_unknown("~", parameters)
        self._wake = threading.Condition()  # new Paths and cancels (and what else the subclass adds) wake its loop

    def _serve(self, on_error: Optional[Callable[[GoalTicket, BaseException], None]] = None) -> ActionType:
        """Create and start the action server (``~client_timeout`` [s], 2.0; 0: off); the constructor's last step."""
        spec = action_type(self.source.action)
        self.server = GoalServer(self.name, spec, self._run, on_cancel=self._on_cancel, on_error=on_error,
                                 client_timeout_s=param_float("~client_timeout", 2.0, 0.0, 600.0))
        self.server.start()
        return spec

    def _on_cancel(self, _ticket: GoalTicket, _replaced: bool) -> None:
        with self._wake:
            self._wake.notify_all()

    # ------------------------------------------------------------------ goals
    def _run(self, ticket: GoalTicket) -> None:
        first = self._first_path(ticket)
        if first is not None:
            self._pursue(ticket, first)

    @abc.abstractmethod
    def _pursue(self, ticket: GoalTicket, first: GoalPath) -> None:
        """Follow the goal until it ends (:meth:`_end`) or is cancelled; a FollowTopic goal's later Paths arrive
        on ``first.topic``."""

    def _first_path(self, ticket: GoalTicket) -> Optional[GoalPath]:
        """The goal's path, or the first Path on the goal's topic; None when the goal ended meanwhile (aborted
        with the reason, or cancelled)."""
        if self.source is GoalSource.PATH:
            return GoalPath(ticket.goal.path, None)
        topic = ticket.goal.topic.data
        problem = topic_name_problem(topic)
        if problem is not None:
            self._end(ticket, GoalOutcome.ABORTED, f"bad topic in the goal: {problem}")
            return None
        fresh_since = fresh_from(ticket.goal.newer_than)
        source = self._topics.subscribe(topic)
        # lockstep: the client's accept hold stands while this waits: the Path comes from a server that publishes
        # its first plan at once (the same simulated time); one that needs time to pass is dropped by the
        # simulator's lockstep timeout (reported), so the wait is bounded either way
        if not self._topics.wait_first(source, self.topic_timeout_s, ticket.cancelled, newer_than=fresh_since):
            if not ticket.cancelled.is_set():
                self._end(ticket, GoalOutcome.ABORTED, source.no_path_reason(self.topic_timeout_s))
            return None
        count = source.count
        assert source.msg is not None
        return GoalPath(source.msg, source, count)

    def _end(self, ticket: GoalTicket, outcome: GoalOutcome, reason: str, pose: Optional[Pose2D] = None) -> None:
        """End the goal as ``outcome`` (code SUCCESS or FAILURE) with ``reason`` and the robot's ``pose`` (None:
        unknown), logged."""
        code = "SUCCESS" if outcome is GoalOutcome.SUCCEEDED else "FAILURE"
        (rospy.loginfo if outcome is GoalOutcome.SUCCEEDED else rospy.logwarn)(
            f"{self.name}: goal #{ticket.number}: {code}: {reason}")
        result_pose = pose_of_xy_yaw(*pose) if pose is not None else pose_of_xy_yaw(math.nan, math.nan, 0.0)
        self.server.finish(ticket, outcome, self.server.result(code, reason, pose=result_pose))

    def _feedback(
        self, ticket: GoalTicket, pose: Pose2D, topic: Optional[TopicPath], twist: Tuple[float, float] = (0.0, 0.0)
    ) -> None:
        """FollowPathFeedback (``pose``, ``twist`` (v [m/s], w [rad/s])) or, with the goal's ``topic``,
        FollowTopicFeedback (``pose``, the newest Path on it)."""
        feedback: Any
        if topic is None:
            feedback = FollowPathFeedback(pose=pose_of_xy_yaw(*pose))
            feedback.twist.linear.x, feedback.twist.angular.z = twist
        else:
            feedback = FollowTopicFeedback(pose=pose_of_xy_yaw(*pose),
                                           path=topic.msg if topic.msg is not None else Path())
        self.server.feedback(ticket, feedback)
