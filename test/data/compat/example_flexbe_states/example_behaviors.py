#!/usr/bin/env python
# ruff: noqa: UP008, PLC0415  (written in FlexBE's / SMACH's own idiom on purpose)
# -*- coding: utf-8 -*-
###########################################################
#               Written in the style of the               #
#               FlexBE App's generated code               #
###########################################################

from flexbe_core import Autonomy, Behavior, ConcurrencyContainer, Logger, OperatableStateMachine, PriorityContainer

from example_flexbe_states.calculation_state import CalculationState
from example_flexbe_states.decision_state import DecisionState
from example_flexbe_states.follow_path_state import FollowPathState
from example_flexbe_states.get_path_state import GetPathState
from example_flexbe_states.log_state import LogState
from example_flexbe_states.publish_string_state import PublishStringState
from example_flexbe_states.subscriber_state import SubscriberState


class CountSM(Behavior):
    '''
    Adds the increment to the value.
    '''

    def __init__(self):
        super(CountSM, self).__init__()
        self.name = 'Count'

        # parameters of this behavior
        self.add_parameter('increment', 1)

    def create(self):
        # x:30 y:365, x:130 y:365
        _state_machine = OperatableStateMachine(outcomes=['finished'], input_keys=['value'], output_keys=['value'])
        _state_machine.userdata.value = 100

        with _state_machine:
            # x:30 y:40
            OperatableStateMachine.add('Add',
                                       CalculationState(calculation=lambda x: x + self.increment),
                                       transitions={'done': 'finished'},
                                       autonomy={'done': Autonomy.Off},
                                       remapping={'input_value': 'value', 'output_value': 'value'})

        return _state_machine


class ExampleSM(Behavior):
    '''
    Counts up to a limit through a sub-behavior, asks the operator before leaving the loop,
    then publishes a text while computing in parallel.
    '''

    def __init__(self):
        super(ExampleSM, self).__init__()
        self.name = 'Example Behavior'

        # parameters of this behavior
        self.add_parameter('limit', 3)
        self.add_parameter('message', 'counting')
        self.add_parameter('topic', '/example_text')

        # references to used behaviors
        self.add_behavior(CountSM, 'Count')

    def create(self):
        # x:30 y:365, x:130 y:365
        _state_machine = OperatableStateMachine(outcomes=['finished', 'failed'], output_keys=['value', 'doubled'])
        _state_machine.userdata.value = 0
        _state_machine.userdata.text = 'hello'

        # x:30 y:365, x:130 y:365
        _sm_parallel_0 = ConcurrencyContainer(outcomes=['finished', 'failed'], input_keys=['value', 'text'],
                                              output_keys=['doubled'], conditions=[
                                                  ('finished', [('Publish', 'done'), ('Double', 'done')])
                                              ])

        with _sm_parallel_0:
            # x:30 y:40
            OperatableStateMachine.add('Publish',
                                       PublishStringState(topic=self.topic),
                                       transitions={'done': 'finished'},
                                       autonomy={'done': Autonomy.Off},
                                       remapping={'value': 'text'})

            # x:230 y:40
            OperatableStateMachine.add('Double',
                                       CalculationState(calculation=lambda x: 2 * x),
                                       transitions={'done': 'finished'},
                                       autonomy={'done': Autonomy.Off},
                                       remapping={'input_value': 'value', 'output_value': 'doubled'})

        with _state_machine:
            # x:30 y:40
            OperatableStateMachine.add('Log',
                                       LogState(text=self.message, severity=Logger.REPORT_HINT),
                                       transitions={'done': 'Count'},
                                       autonomy={'done': Autonomy.Off})

            # x:30 y:140
            OperatableStateMachine.add('Count',
                                       self.use_behavior(CountSM, 'Count'),
                                       transitions={'finished': 'Check'},
                                       autonomy={'finished': Autonomy.Inherit},
                                       remapping={'value': 'value'})

            # x:30 y:240
            OperatableStateMachine.add('Check',
                                       DecisionState(outcomes=['again', 'done'],
                                                     conditions=lambda v: 'done' if v >= self.limit else 'again'),
                                       transitions={'again': 'Count', 'done': 'Parallel'},
                                       autonomy={'again': Autonomy.Off, 'done': Autonomy.High},
                                       remapping={'input_value': 'value'})

            # x:30 y:340
            OperatableStateMachine.add('Parallel',
                                       _sm_parallel_0,
                                       transitions={'finished': 'finished', 'failed': 'failed'},
                                       autonomy={'finished': Autonomy.Inherit, 'failed': Autonomy.Inherit},
                                       remapping={'value': 'value', 'text': 'text', 'doubled': 'doubled'})

        return _state_machine


class ListenSM(Behavior):
    '''
    Waits for a text message; a priority container logs a hint first.
    '''

    def __init__(self):
        super(ListenSM, self).__init__()
        self.name = 'Listen'
        self.add_parameter('topic', '/example_text')

    def create(self):
        from std_msgs.msg import String

        # x:30 y:365, x:130 y:365
        _state_machine = OperatableStateMachine(outcomes=['finished', 'failed'], output_keys=['message'])

        # x:30 y:365
        _sm_first_0 = PriorityContainer(outcomes=['finished'])

        with _sm_first_0:
            # x:30 y:40
            OperatableStateMachine.add('Hint',
                                       LogState(text='listening', severity=Logger.REPORT_HINT),
                                       transitions={'done': 'finished'},
                                       autonomy={'done': Autonomy.Off})

        with _state_machine:
            # x:30 y:40
            OperatableStateMachine.add('First',
                                       _sm_first_0,
                                       transitions={'finished': 'Receive'},
                                       autonomy={'finished': Autonomy.Inherit})

            # x:30 y:140
            OperatableStateMachine.add('Receive',
                                       SubscriberState(topic=self.topic, msg_type=String, clear=False),
                                       transitions={'received': 'finished', 'unavailable': 'failed'},
                                       autonomy={'received': Autonomy.Off, 'unavailable': Autonomy.Off},
                                       remapping={'message': 'message'})

        return _state_machine


class PlanAndFollowSM(Behavior):
    '''
    Plans a path with a GetPath server and follows it with a FollowPath server.
    '''

    def __init__(self):
        super(PlanAndFollowSM, self).__init__()
        self.name = 'Plan and Follow'
        self.add_parameter('planner_topic', 'get_path')
        self.add_parameter('follower_topic', 'follow_path')

    def create(self):
        # x:30 y:365, x:130 y:365
        _state_machine = OperatableStateMachine(outcomes=['finished', 'failed'], input_keys=['goal'],
                                                output_keys=['plan'])

        with _state_machine:
            # x:30 y:40
            OperatableStateMachine.add('Plan',
                                       GetPathState(action_topic=self.planner_topic),
                                       transitions={'planned': 'Follow', 'failed': 'failed'},
                                       autonomy={'planned': Autonomy.Off, 'failed': Autonomy.Off},
                                       remapping={'goal': 'goal', 'plan': 'plan'})

            # x:30 y:140
            OperatableStateMachine.add('Follow',
                                       FollowPathState(action_topic=self.follower_topic),
                                       transitions={'done': 'finished', 'failed': 'failed'},
                                       autonomy={'done': Autonomy.Off, 'failed': Autonomy.Off},
                                       remapping={'plan': 'plan'})

        return _state_machine
