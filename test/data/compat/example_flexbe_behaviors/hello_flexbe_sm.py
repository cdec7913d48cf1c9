#!/usr/bin/env python
# -*- coding: utf-8 -*-
# ruff: noqa  (laid out as the FlexBE App generates behaviors: tabs, header, MANUAL tags; on purpose)
###########################################################
#               WARNING: Generated code!                  #
#              **************************                 #
# Manual changes may get lost if file is generated again. #
# Only code inside the [MANUAL] tags will be kept.        #
###########################################################

from flexbe_core import Autonomy, Behavior, ConcurrencyContainer, Logger, OperatableStateMachine, PriorityContainer
from example_flexbe_states.calculation_state import CalculationState
from example_flexbe_states.decision_state import DecisionState
from example_flexbe_states.log_state import LogState
# Additional imports can be added inside the following tags
# [MANUAL_IMPORT]
import math
# [/MANUAL_IMPORT]


'''
Created on Sat Jan 06 2024
@author: flex_nav tests
'''
class HelloFlexBESM(Behavior):
	'''
	Greets, squares a number until it passes a limit, checks it in parallel with a log line, and reports.
	'''


	def __init__(self):
		super(HelloFlexBESM, self).__init__()
		self.name = 'Hello FlexBE'

		# parameters of this behavior
		self.add_parameter('greeting', 'Hello from a generated behavior')
		self.add_parameter('limit', 100)

		# references to used behaviors

		# Additional initialization code can be added inside the following tags
		# [MANUAL_INIT]
		self._offset = 1
		# [/MANUAL_INIT]

		# Behavior comments:

		# O 40 200
		# Squares the value until it is over the limit



	def create(self):
		# x:530 y:40, x:530 y:140
		_state_machine = OperatableStateMachine(outcomes=['finished', 'failed'], input_keys=['number'], output_keys=['result'])
		_state_machine.userdata.number = 2
		_state_machine.userdata.result = 0

		# Additional creation code can be added inside the following tags
		# [MANUAL_CREATE]
		square = lambda x: int(math.pow(x, 2)) + self._offset - 1
		# [/MANUAL_CREATE]

		# x:30 y:365, x:130 y:365
		_sm_report_0 = ConcurrencyContainer(outcomes=['done'], input_keys=['result'], conditions=[
										('done', [('Log', 'done'), ('Check', 'big')])
										])

		with _sm_report_0:
			# x:30 y:40
			OperatableStateMachine.add('Log',
										LogState(text="reporting", severity=Logger.REPORT_INFO),
										transitions={'done': 'done'},
										autonomy={'done': Autonomy.Off})

			# x:230 y:40
			OperatableStateMachine.add('Check',
										DecisionState(outcomes=['big', 'small'], conditions=lambda v: 'big' if v > 0 else 'small'),
										transitions={'big': 'done', 'small': 'done'},
										autonomy={'big': Autonomy.Off, 'small': Autonomy.Off},
										remapping={'input_value': 'result'})


		with _state_machine:
			# x:30 y:40
			OperatableStateMachine.add('Greet',
										LogState(text=self.greeting, severity=Logger.REPORT_HINT),
										transitions={'done': 'Square'},
										autonomy={'done': Autonomy.Off})

			# x:30 y:140
			OperatableStateMachine.add('Square',
										CalculationState(calculation=square),
										transitions={'done': 'Enough'},
										autonomy={'done': Autonomy.Off},
										remapping={'input_value': 'number', 'output_value': 'number'})

			# x:30 y:240
			OperatableStateMachine.add('Enough',
										DecisionState(outcomes=['yes', 'no'], conditions=lambda v: 'yes' if v > self.limit else 'no'),
										transitions={'yes': 'Copy', 'no': 'Square'},
										autonomy={'yes': Autonomy.Low, 'no': Autonomy.Off},
										remapping={'input_value': 'number'})

			# x:230 y:240
			OperatableStateMachine.add('Copy',
										CalculationState(calculation=lambda x: x),
										transitions={'done': 'Report'},
										autonomy={'done': Autonomy.Off},
										remapping={'input_value': 'number', 'output_value': 'result'})

			# x:230 y:340
			OperatableStateMachine.add('Report',
										_sm_report_0,
										transitions={'done': 'finished'},
										autonomy={'done': Autonomy.Inherit},
										remapping={'result': 'result'})


		return _state_machine


	# Private functions can be added inside the following tags
	# [MANUAL_FUNC]
	
	# [/MANUAL_FUNC]
