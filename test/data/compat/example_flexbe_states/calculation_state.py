#!/usr/bin/env python
# ruff: noqa: UP008, UP031  (written in FlexBE's / SMACH's own idiom on purpose)
from flexbe_core import EventState, Logger


class CalculationState(EventState):
    """
    Applies a function to the input value and writes the result.

    -- calculation  function  The function applied to the input value.

    ># input_value  object    Input of the calculation.

    #> output_value object    Result of the calculation.

    <= done                   The result was written.
    """

    def __init__(self, calculation):
        super(CalculationState, self).__init__(outcomes=['done'], input_keys=['input_value'],
                                               output_keys=['output_value'])
        self._calculation = calculation
        self._calculation_result = None

    def on_enter(self, userdata):
        try:
            self._calculation_result = self._calculation(userdata.input_value)
        except Exception as e:
            Logger.logwarn('Failed to execute calculation function!\n%s' % str(e))
            raise

    def execute(self, userdata):
        userdata.output_value = self._calculation_result
        return 'done'
