#!/usr/bin/env python
# ruff: noqa: UP008  (written in FlexBE's / SMACH's own idiom on purpose)
from flexbe_core import EventState
from flexbe_core.proxy import ProxyPublisher
from std_msgs.msg import String


class PublishStringState(EventState):
    """
    Publishes the input string on a topic once, when entered.

    -- topic     string  Topic to publish on.

    ># value     string  The text to publish.

    <= done              The message was published.
    """

    def __init__(self, topic):
        super(PublishStringState, self).__init__(outcomes=['done'], input_keys=['value'])
        self._topic = topic
        self._pub = ProxyPublisher({self._topic: String})

    def on_enter(self, userdata):
        self._pub.publish(self._topic, String(data=userdata.value))

    def execute(self, userdata):
        return 'done'
