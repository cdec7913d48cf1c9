#!/usr/bin/env python
# ruff: noqa: UP008, UP031  (written in FlexBE's / SMACH's own idiom on purpose)
from flexbe_core import EventState, Logger
from flexbe_core.proxy import ProxySubscriberCached


class SubscriberState(EventState):
    """
    Waits for a message on a topic and writes it to userdata.

    -- topic     string  Topic to listen to.
    -- msg_type  class   Message class of the topic.
    -- clear     bool    Drop a message that arrived before the state was entered.

    #> message   object  The received message.

    <= received          A message was received.
    <= unavailable       The topic is not subscribed.
    """

    def __init__(self, topic, msg_type, clear=False):
        super(SubscriberState, self).__init__(outcomes=['received', 'unavailable'], output_keys=['message'])
        self._topic = topic
        self._clear = clear
        self._sub = ProxySubscriberCached({self._topic: msg_type})

    def on_enter(self, userdata):
        if self._clear and self._sub.has_msg(self._topic):
            self._sub.remove_last_msg(self._topic)

    def execute(self, userdata):
        if not self._sub.is_available(self._topic):
            Logger.logwarn('Topic %s is not subscribed' % self._topic)
            return 'unavailable'
        if self._sub.has_msg(self._topic):
            userdata.message = self._sub.get_last_msg(self._topic)
            self._sub.remove_last_msg(self._topic)
            return 'received'
        return None
