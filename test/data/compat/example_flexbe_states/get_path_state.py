#!/usr/bin/env python
# ruff: noqa: UP008, UP031  (written in FlexBE's / SMACH's own idiom on purpose)
from actionlib_msgs.msg import GoalStatus
from flexbe_core import EventState, Logger
from flexbe_core.proxy import ProxyActionClient

from flex_nav.msg import GetPathAction, GetPathGoal


class GetPathState(EventState):
    """
    Asks a flex_nav GetPath server for a path to the goal pose.

    -- action_topic  string  Name of the GetPath action server.

    ># goal          PoseStamped  Where to go.

    #> plan          Path         The path found.

    <= planned                    A path was found.
    <= failed                     The server did not find a path (or is not there).
    """

    def __init__(self, action_topic):
        super(GetPathState, self).__init__(outcomes=['planned', 'failed'], input_keys=['goal'],
                                           output_keys=['plan'])
        self._action_topic = action_topic
        self._client = ProxyActionClient({self._action_topic: GetPathAction}, wait_duration=5)
        self._failed = False

    def on_enter(self, userdata):
        self._failed = False
        goal = GetPathGoal()
        goal.pose = userdata.goal
        try:
            self._client.send_goal(self._action_topic, goal)
        except Exception as e:
            Logger.logwarn('Failed to send the GetPath goal:\n%s' % str(e))
            self._failed = True

    def execute(self, userdata):
        if self._failed:
            return 'failed'
        if self._client.has_result(self._action_topic):
            result = self._client.get_result(self._action_topic)
            if self._client.get_state(self._action_topic) == GoalStatus.SUCCEEDED:
                userdata.plan = result.plan
                return 'planned'
            Logger.logwarn('GetPath failed: %s' % result.message)
            return 'failed'
        return None

    def on_exit(self, userdata):
        if self._client.is_active(self._action_topic):
            self._client.cancel(self._action_topic)
            Logger.loginfo('Cancelled active action goal.')
