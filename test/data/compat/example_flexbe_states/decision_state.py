#!/usr/bin/env python
# ruff: noqa: UP008, UP031  (written in FlexBE's / SMACH's own idiom on purpose)
from flexbe_core import EventState, Logger


class DecisionState(EventState):
    """
    Evaluates a condition function on the input and returns its result as the outcome.

    -- outcomes    string[]  The outcomes the condition may return.
    -- conditions  function  Maps the input value to one of the outcomes.

    ># input_value object    Input of the condition.

    <= outcomes              As returned by the condition.
    """

    def __init__(self, outcomes, conditions):
        super(DecisionState, self).__init__(outcomes=outcomes, input_keys=['input_value'])
        self._conditions = conditions
        self._my_outcomes = outcomes

    def execute(self, userdata):
        outcome = self._conditions(userdata.input_value)
        if outcome in self._my_outcomes:
            return outcome
        Logger.logwarn('Returned outcome %s is not registered' % str(outcome))
        return None
