#!/usr/bin/env python
# ruff: noqa: UP031  (written in FlexBE's / SMACH's own idiom on purpose)
"""A SMACH tutorial-style script: only `import smach`, nothing of flex_nav.

Run through flex_nav's alias (flex_nav.compat.install_aliases()); prints one line per check and
"ALL OK" at the end. Every check asserts, so a semantic difference fails the script.
"""

import threading

import smach


# --- the classic two-state example with userdata remapping ------------------------------------
class Foo(smach.State):
    def __init__(self):
        smach.State.__init__(self, outcomes=['outcome1', 'outcome2'],
                             input_keys=['foo_counter_in'], output_keys=['foo_counter_out'])

    def execute(self, userdata):
        smach.loginfo('Executing state FOO')
        if userdata.foo_counter_in < 3:
            userdata.foo_counter_out = userdata.foo_counter_in + 1
            return 'outcome1'
        return 'outcome2'


class Bar(smach.State):
    def __init__(self):
        smach.State.__init__(self, outcomes=['outcome1'], input_keys=['bar_counter_in'])

    def execute(self, userdata):
        smach.loginfo('Counter = %f' % userdata.bar_counter_in)
        return 'outcome1'


def counting_machine():
    sm = smach.StateMachine(outcomes=['outcome4'])
    sm.userdata.sm_counter = 0
    with sm:
        smach.StateMachine.add('FOO', Foo(), transitions={'outcome1': 'BAR', 'outcome2': 'outcome4'},
                               remapping={'foo_counter_in': 'sm_counter', 'foo_counter_out': 'sm_counter'})
        smach.StateMachine.add('BAR', Bar(), transitions={'outcome1': 'FOO'},
                               remapping={'bar_counter_in': 'sm_counter'})
    return sm


sm = counting_machine()
visited = []
sm.register_transition_cb(lambda ud, active_states: visited.append(active_states[0]))
outcome = sm.execute()
assert outcome == 'outcome4', outcome
assert sm.userdata.sm_counter == 3
assert visited == ['BAR', 'FOO', 'BAR', 'FOO', 'BAR', 'FOO'], visited
print('state machine:', outcome, 'counter', sm.userdata.sm_counter)


# --- nested machines, CBState with cb_interface, Sequence ------------------------------------------
@smach.cb_interface(outcomes=['added'], input_keys=['a', 'b'], output_keys=['total'])
def add_cb(ud, scale):
    ud.total = scale * (ud.a + ud.b)
    return 'added'


top = smach.StateMachine(outcomes=['done', 'failed'], output_keys=['result'])
top.userdata.x = 2
top.userdata.y = 5
with top:
    inner = smach.StateMachine(outcomes=['ok'], input_keys=['a', 'b'], output_keys=['total'])
    with inner:
        smach.StateMachine.add('ADD', smach.CBState(add_cb, cb_args=[10]), transitions={'added': 'ok'})
    smach.StateMachine.add('INNER', inner, transitions={'ok': 'SEQ'},
                           remapping={'a': 'x', 'b': 'y', 'total': 'result'})
    seq = smach.Sequence(outcomes=['succeeded', 'aborted'], connector_outcome='succeeded')
    with seq:
        smach.Sequence.add('S1', smach.CBState(lambda ud: 'succeeded', outcomes=['succeeded', 'aborted']))
        smach.Sequence.add('S2', smach.CBState(lambda ud: 'succeeded', outcomes=['succeeded', 'aborted']))
    smach.StateMachine.add('SEQ', seq, transitions={'succeeded': 'done', 'aborted': 'failed'})
parent = smach.UserData()
outcome = top.execute(parent)
assert outcome == 'done', outcome
assert parent.result == 70, parent.result
print('nested:', outcome, 'result', parent.result)


# --- concurrence with a monitor that preempts the other child --------------------------------------
class Monitor(smach.State):
    def __init__(self):
        smach.State.__init__(self, outcomes=['triggered'])

    def execute(self, ud):
        return 'triggered'


class Worker(smach.State):
    def __init__(self):
        smach.State.__init__(self, outcomes=['finished', 'preempted'])
        self.stopped = threading.Event()

    def execute(self, ud):
        while not self.preempt_requested():
            self.stopped.wait(0.01)
        self.service_preempt()
        return 'preempted'


cc = smach.Concurrence(outcomes=['stopped', 'finished'], default_outcome='finished',
                       outcome_map={'stopped': {'MONITOR': 'triggered', 'WORKER': 'preempted'}},
                       child_termination_cb=lambda outcomes: outcomes['MONITOR'] is not None)
with cc:
    smach.Concurrence.add('MONITOR', Monitor())
    smach.Concurrence.add('WORKER', Worker())
outcome = cc.execute()
assert outcome == 'stopped', outcome
print('concurrence:', outcome)


# --- iterator --------------------------------------------------------------------------------------------
it = smach.Iterator(outcomes=['succeeded'], input_keys=[], output_keys=['items_seen'], it=lambda: range(4),
                    it_label='index', exhausted_outcome='succeeded')
it.userdata.items_seen = []
with it:
    body = smach.CBState(lambda ud: ud.items_seen.append(ud.index) or 'continue', outcomes=['continue'],
                         input_keys=['index', 'items_seen'], output_keys=['items_seen'])
    smach.Iterator.set_contained_state('BODY', body, loop_outcomes=['continue'])
it_parent = smach.UserData()
outcome = it.execute(it_parent)
assert outcome == 'succeeded' and it_parent.items_seen == [0, 1, 2, 3], (outcome, it_parent.items_seen)
print('iterator:', outcome, it_parent.items_seen)


# --- preempting a running state machine from another thread -----------------------------------------
class Wait(smach.State):
    def __init__(self):
        smach.State.__init__(self, outcomes=['done', 'preempted'])
        self.started = threading.Event()

    def execute(self, ud):
        self.started.set()
        while not self.preempt_requested():
            threading.Event().wait(0.01)
        self.service_preempt()
        return 'preempted'


waiting = Wait()
pm = smach.StateMachine(outcomes=['done', 'preempted'])
with pm:
    smach.StateMachine.add('WAIT', waiting, transitions={'done': 'done', 'preempted': 'preempted'})
result = []
runner = threading.Thread(target=lambda: result.append(pm.execute()))
runner.start()
assert waiting.started.wait(5.0)
pm.request_preempt()
runner.join(5.0)
assert result == ['preempted'], result
assert not pm.preempt_requested()
print('preempt:', result[0])


# --- errors are typed -----------------------------------------------------------------------------------------
broken = smach.StateMachine(outcomes=['done'])
with broken:
    smach.StateMachine.add('BAD', smach.CBState(lambda ud: 1 / 0, outcomes=['done']), transitions={'done': 'done'})
try:
    broken.execute()
except smach.InvalidUserCodeError as err:
    assert isinstance(err.__cause__, ZeroDivisionError)
    print('user code error:', type(err).__name__)
else:
    raise AssertionError('InvalidUserCodeError expected')

print('ALL OK')
