#!/usr/bin/env python
# ruff: noqa: UP008, UP031  (written in FlexBE's / SMACH's own idiom on purpose)
from actionlib_msgs.msg import GoalStatus
from flexbe_core import EventState, Logger
from flexbe_core.proxy import ProxyActionClient

from flex_nav.msg import FollowPathAction, FollowPathGoal


class FollowPathState(EventState):
    """
    Sends a path to a flex_nav FollowPath server and waits until it is followed.

    -- action_topic  string  Name of the FollowPath action server.

    ># plan          Path    The path to follow.

    <= done                  The path was followed.
    <= failed                The server failed (or is not there).
    """

    def __init__(self, action_topic):
        super(FollowPathState, self).__init__(outcomes=['done', 'failed'], input_keys=['plan'])
        self._action_topic = action_topic
        self._client = ProxyActionClient({self._action_topic: FollowPathAction}, wait_duration=5)
        self._failed = False

    def on_enter(self, userdata):
        self._failed = False
        try:
            self._client.send_goal(self._action_topic, FollowPathGoal(path=userdata.plan))
        except Exception as e:
            Logger.logwarn('Failed to send the FollowPath goal:\n%s' % str(e))
            self._failed = True

    def execute(self, userdata):
        if self._failed:
            return 'failed'
        if self._client.has_result(self._action_topic):
            if self._client.get_state(self._action_topic) == GoalStatus.SUCCEEDED:
                return 'done'
            return 'failed'
        return None

    def on_exit(self, userdata):
        if self._client.is_active(self._action_topic):
            self._client.cancel(self._action_topic)
            Logger.loginfo('Cancelled active action goal.')
