"""What :class:`flex_nav.ros.goal_server.GoalServer` needs of a SimpleActionServer beyond actionlib's public API.

Everything else GoalServer does goes through the public methods (``register_goal_callback``,
``register_preempt_callback``, ``accept_new_goal``, ``is_active``, ``set_*``, ``publish_feedback``, and
ActionServer's ``register_goal_callback``). The items below have no public counterpart in actionlib or rospy
(Noetic: ``actionlib/simple_action_server.py``, ``action_server.py``, ``server_goal_handle.py``;
``rospy/topics.py``); they are gathered here so that a change in either library shows up in one module.
"""

from __future__ import annotations

import contextlib
import enum
from typing import Any, Callable, Iterator, List, Optional, Tuple

import actionlib
import rospy


class RememberedGoal(enum.Enum):
    """The two goal handles SimpleActionServer keeps (the attribute names are actionlib's)."""

    CURRENT = "current_goal"
    NEXT = "next_goal"


class SimpleServerInternals:
    """The internals of one ``actionlib.SimpleActionServer`` that GoalServer relies on."""

    def __init__(self, server: actionlib.SimpleActionServer) -> None:
        self._server = server

    @contextlib.contextmanager
    def locked(self) -> Iterator[None]:
        """Both of the server's locks, in actionlib's order (the ActionServer's, then the SimpleActionServer's).

        Why not public: a check of the current goal and the ``set_succeeded``/``set_aborted`` that follows it
        must be one step, or a goal arriving in between is ended in the old goal's place. actionlib takes the
        same two locks around its own callbacks and setters but offers no way to hold them; both are
        re-entrant, so this may be taken inside actionlib's callbacks too (the ActionServer's lock is held
        there already, and taking the SimpleActionServer's after it keeps actionlib's order)."""
        with self._server.action_server.lock, self._server.lock:
            yield

    def intercept_goals(self, before: Callable[[Any], None]) -> None:
        """Call ``before(goal_handle)`` for every incoming goal, ahead of SimpleActionServer's own handling
        (with the ActionServer's lock held, as actionlib calls its goal callback).

        Why not public: ActionServer's ``register_goal_callback`` is public, but SimpleActionServer's handler
        it replaces (``internal_goal_callback``, which compares the goal's stamp with the goals it remembers)
        is public only by name; there is no hook that runs before that comparison."""
        simple_goal_callback = self._server.internal_goal_callback

        def goal_callback(goal_handle: Any) -> None:
            before(goal_handle)
            simple_goal_callback(goal_handle)

        self._server.action_server.register_goal_callback(goal_callback)

    def remembered_stamp(self, which: RememberedGoal) -> Optional[rospy.Time]:
        """The stamp of the goal SimpleActionServer keeps as ``which``; None when it keeps none.

        Why not public: SimpleActionServer exposes only the goal message of the current goal (the return of
        ``accept_new_goal``), neither handle nor their stamps, which its goal callback compares new goals with."""
        handle = getattr(self._server, which.value)
        if handle.get_goal() is None:
            return None
        stamp: rospy.Time = handle.get_goal_id().stamp
        return stamp

    def forget(self, which: RememberedGoal) -> None:
        """Make SimpleActionServer keep no goal as ``which`` (an empty handle, as after its construction).

        Why not public: it never lets go of a goal by itself; after ROS time jumped back, the old timeline's
        goal would make it cancel every new goal (stamped earlier) until time caught up again."""
        setattr(self._server, which.value, actionlib.ServerGoalHandle())

    def sender_of_current_goal(self) -> str:
        """The node that published the current goal ("" if unknown).

        Why not public: ``get_goal()`` returns the inner goal; only the ActionGoal message that arrived on the
        goal topic carries rospy's ``_connection_header`` (with the sender's ``callerid``), and rospy has no
        other way to tell a subscriber callback who published."""
        tracker = getattr(self._server.current_goal, "status_tracker", None)
        header = getattr(getattr(tracker, "goal", None), "_connection_header", None)
        sender = header.get("callerid", "") if isinstance(header, dict) else ""
        return sender if isinstance(sender, str) else ""

    def status_connections(self) -> List[Tuple[int, str]]:
        """(connection id, caller id) of every node connected to the server's status topic.

        Why not public: rospy's Publisher tells only the number of its connections; the caller ids and
        connection ids are in its ``impl`` (the getBusInfo data). The master's system state would name the
        subscribers but not tell a restarted node's new connection from its predecessor's, and asking it
        blocks while the master is out of reach."""
        impl = getattr(self._server.action_server.status_pub, "impl", None)
        return [(info[0], info[1]) for info in impl.get_stats_info()] if impl is not None else []
