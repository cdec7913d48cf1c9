"""flexbe_core.proxy: FlexBE's method names, bound to ONE behavior's connections (FakeHub), never shared."""

from __future__ import annotations

from typing import List

import pytest
from unit.compat.compat_testlib import ABORTED, ACTIVE, PREEMPTED, SUCCEEDED, FakeHub

from flex_nav.behavior import Autonomy, BehaviorContext, BehaviorExecutor, BehaviorStatus, ManualClock, using_context
from flex_nav.behavior.events import LogEvent
from flex_nav.exceptions import NotReadyError


class Topic:
    """A message class (FakePublisher checks the type of what is published)."""

    def __init__(self, data=None):
        self.data = data


def context(name="test", hub=None):
    ctx = BehaviorContext(
        name, clock=ManualClock(), proxies=hub if hub is not None else FakeHub(), autonomy=Autonomy.FULL
    )
    logs: List[LogEvent] = []
    ctx.hooks.log.append(logs.append)
    return ctx, logs


# --- binding: which behavior a proxy belongs to -------------------------------------------------------------------
def test_two_behaviors_in_one_process_never_share_connections(aliases):
    from example_flexbe_states.example_behaviors import ExampleSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    first_hub, second_hub = FakeHub(), FakeHub()
    first, _ = context("first", first_hub)
    second, _ = context("second", second_hub)
    first_behavior = build_behavior(ExampleSM, context=first, parameters={"limit": 1, "topic": "/shared"})
    second_behavior = build_behavior(ExampleSM, context=second, parameters={"limit": 2, "topic": "/shared"})
    publish_first = first_behavior.root["Parallel"]["Publish"]
    publish_second = second_behavior.root["Parallel"]["Publish"]
    assert publish_first._pub._binding.peek() is first_hub
    assert publish_second._pub._binding.peek() is second_hub
    first_run = BehaviorExecutor(first_behavior, context=first)
    second_run = BehaviorExecutor(second_behavior, context=second)
    for _ in range(200):  # interleaved in one thread: each tick runs under its own behavior's context
        first_run.spin_once()
        second_run.spin_once()
        first.clock.advance(0.1)
        second.clock.advance(0.1)
    assert first_run.status is BehaviorStatus.FINISHED and second_run.status is BehaviorStatus.FINISHED
    assert first_run.result().outputs["value"] == 1 and second_run.result().outputs["value"] == 2
    assert [m.data for m in first_hub.publishers["/shared"].sent] == ["hello"]
    assert [m.data for m in second_hub.publishers["/shared"].sent] == ["hello"]
    assert first_hub.publishers["/shared"] is not second_hub.publishers["/shared"]


def test_proxy_created_outside_a_behavior_binds_when_first_used_in_one(aliases):
    from example_flexbe_states.publish_string_state import PublishStringState  # noqa: PLC0415
    from flexbe_core import OperatableStateMachine  # noqa: PLC0415

    state = PublishStringState(topic="/late")  # e.g. loaded offline, without the runner's context
    assert not state._pub._binding.bound
    assert state._pub.is_available("/late")  # declared, will be created on first use
    sm = OperatableStateMachine(outcomes=["finished"])
    sm.userdata.value = "bound late"
    with sm:
        OperatableStateMachine.add("Pub", state, transitions={"done": "finished"})
    ctx, _ = context()
    result = BehaviorExecutor(sm, context=ctx).run(timeout_s=10.0)
    assert result.status is BehaviorStatus.FINISHED, result.reason
    assert [m.data for m in ctx.proxies.publishers["/late"].sent] == ["bound late"]
    assert state._pub._binding.peek() is ctx.proxies


def test_using_a_proxy_outside_any_behavior_is_not_ready(aliases):
    from flexbe_core.proxy import ProxyPublisher  # noqa: PLC0415

    pub = ProxyPublisher({"/x": Topic})
    with pytest.raises(NotReadyError, match="outside a behavior that has ROS proxies"):
        pub.publish("/x", Topic())


# --- ProxyPublisher ----------------------------------------------------------------------------------------------
def test_publisher_publish_wait_for_any_and_unknown_topic():
    ctx, _ = context()
    with using_context(ctx):
        from flex_nav.compat.flexbe_core.proxy import ProxyPublisher  # noqa: PLC0415

        pub = ProxyPublisher({"/a": Topic})
        other_state_pub = ProxyPublisher()  # another state of the same behavior
        other_state_pub.publish("/a", Topic(1))  # shared per behavior, as in FlexBE
        pub.publish("/a", Topic(2))
        assert [m.data for m in ctx.proxies.publishers["/a"].sent] == [1, 2]
        assert pub.is_available("/a") and not pub.is_available("/b")
        assert pub.wait_for_any("/a", timeout=0.05) is False  # nobody listens: the bounded wait runs out
        ctx.proxies.publishers["/a"].connections = 1
        assert pub.wait_for_any("/a", timeout=5.0) is True
        with pytest.raises(NotReadyError, match=r"no publisher for topic '/b'.*this proxy created: /a"):
            pub.publish("/b", Topic())


# --- ProxySubscriberCached ------------------------------------------------------------------------------------------
def test_subscriber_cache_buffer_and_callbacks():
    ctx, _ = context()
    with using_context(ctx):
        from flex_nav.compat.flexbe_core.proxy import ProxySubscriberCached  # noqa: PLC0415

        received: List[Topic] = []
        sub = ProxySubscriberCached({"/cached": Topic})
        sub.subscribe("/buffered", Topic, callback=received.append, buffered=True)
        cached, buffered = ctx.proxies.subscriptions["/cached"], ctx.proxies.subscriptions["/buffered"]
        assert not sub.has_msg("/cached") and sub.get_last_msg("/cached") is None
        cached.inject(Topic("a"))
        assert sub.has_msg("/cached") and sub.get_last_msg("/cached").data == "a"
        sub.remove_last_msg("/cached")
        assert not sub.has_msg("/cached")
        for value in (1, 2, 3):
            buffered.inject(Topic(value))
        assert [m.data for m in received] == [1, 2, 3]
        assert sub.has_buffered("/buffered")
        assert sub.get_from_buffer("/buffered").data == 1
        sub.remove_last_msg("/buffered", clear_buffer=True)
        assert not sub.has_buffered("/buffered") and not sub.has_msg("/buffered")
        assert sub.get_from_buffer("/buffered") is None
        sub.unsubscribe_topic("/buffered")  # this proxy's callback goes; the shared connection stays
        buffered.inject(Topic(4))
        assert len(received) == 3 and sub.has_msg("/buffered")
        sub.disable_buffer("/buffered")
        buffered.inject(Topic(5))
        assert not sub.has_buffered("/buffered")
        sub.enable_buffer("/cached")
        cached.inject(Topic("b"))
        assert sub.get_from_buffer("/cached").data == "b"
        assert sub.is_available("/cached") and not sub.is_available("/nope") and not sub.has_msg("/nope")
        with pytest.raises(NotReadyError, match=r"topic '/nope' is not subscribed.*subscribed: /cached, /buffered"):
            sub.get_last_msg("/nope")


def test_subscriber_state_from_the_library_receives_a_message(aliases):
    from example_flexbe_states.example_behaviors import ListenSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    ctx, logs = context()
    executor = BehaviorExecutor(build_behavior(ListenSM, context=ctx, parameters={"topic": "/heard"}), context=ctx)
    assert executor.run(timeout_s=5.0, stop_on_timeout=False).status is BehaviorStatus.RUNNING
    assert executor.active_paths() == ("/Receive",)
    from std_msgs.msg import String  # noqa: PLC0415

    ctx.proxies.subscriptions["/heard"].inject(String(data="hi"))
    result = executor.run(timeout_s=5.0)
    assert result.status is BehaviorStatus.FINISHED and result.outputs["message"].data == "hi"
    assert [(e.level.name, e.message) for e in logs] == [("HINT", "listening")]


# --- ProxyActionClient -----------------------------------------------------------------------------------------------
def test_action_client_goal_result_feedback_cancel():
    ctx, logs = context()
    with using_context(ctx):
        from flex_nav.compat.flexbe_core.proxy import ProxyActionClient  # noqa: PLC0415

        client = ProxyActionClient({"/move": Topic}, wait_duration=3)
        fake = ctx.proxies.action_clients["/move"]
        assert fake.availability_waits == [3.0]  # setupClient waited (bounded) for the server
        assert client.is_available("/move") and not client.is_available("/other")
        client.send_goal("/move", "goal-1")
        assert fake.goals == ["goal-1"] and client.is_active("/move")
        assert client.get_state("/move") == ACTIVE
        assert not client.has_result("/move") and not client.has_feedback("/move")
        fake.give_feedback("halfway")
        assert client.has_feedback("/move") and client.get_feedback("/move") == "halfway"
        client.remove_feedback("/move")
        assert not client.has_feedback("/move")
        fake.finish(SUCCEEDED, "result-1")
        assert client.has_result("/move") and client.get_result("/move") == "result-1"
        assert client.get_state("/move") == SUCCEEDED and not client.is_active("/move")
        client.remove_result("/move")
        assert not client.has_result("/move")
        client.send_goal("/move", "goal-2")
        client.cancel("/move")
        assert fake.cancels == 1 and client.get_state("/move") == PREEMPTED
        with pytest.raises(NotReadyError, match=r"action '/other' is not set up.*set up: /move"):
            client.send_goal("/other", "goal")
    assert logs == []


def test_action_client_without_server_logs_at_setup_and_fails_loudly_on_send():
    ctx, logs = context(hub=FakeHub(servers_up=False))
    with using_context(ctx):
        from flex_nav.compat.flexbe_core.proxy import ProxyActionClient  # noqa: PLC0415

        client = ProxyActionClient({"/move": Topic}, wait_duration=1)
        assert not client.is_available("/move")
        with pytest.raises(NotReadyError, match="/move is not available"):
            client.send_goal("/move", "goal")
    assert [(e.level.name, e.message) for e in logs] == [
        ("ERROR", "Action client /move timed out: no server after 1.0 s")
    ]


def test_plan_and_follow_behavior_with_action_states(aliases):
    from example_flexbe_states.example_behaviors import PlanAndFollowSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    from flex_nav.msg import GetPathResult  # noqa: PLC0415

    ctx, _ = context()
    executor = BehaviorExecutor(build_behavior(PlanAndFollowSM, context=ctx), context=ctx, inputs={"goal": "pose"})
    planner, follower = ctx.proxies.action_clients["get_path"], ctx.proxies.action_clients["follow_path"]
    executor.run(timeout_s=1.0, stop_on_timeout=False)
    assert [g.pose for g in planner.goals] == ["pose"]
    result = GetPathResult(code=GetPathResult.SUCCESS, message="ok")
    result.plan.header.frame_id = "map"
    planner.finish(SUCCEEDED, result)
    executor.run(timeout_s=1.0, stop_on_timeout=False)
    assert executor.active_paths() == ("/Follow",)
    assert follower.goals[0].path.header.frame_id == "map"
    follower.finish(SUCCEEDED, None)
    final = executor.run(timeout_s=1.0)
    assert final.status is BehaviorStatus.FINISHED and final.outcome == "finished"
    assert final.outputs["plan"].header.frame_id == "map"


def test_preempting_a_behavior_cancels_the_active_goal_in_on_exit(aliases):
    from example_flexbe_states.example_behaviors import PlanAndFollowSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    ctx, logs = context()
    executor = BehaviorExecutor(build_behavior(PlanAndFollowSM, context=ctx), context=ctx, inputs={"goal": "pose"})
    executor.run(timeout_s=1.0, stop_on_timeout=False)
    planner = ctx.proxies.action_clients["get_path"]
    assert planner.is_active()
    executor.preempt()
    result = executor.run(timeout_s=1.0)
    assert result.status is BehaviorStatus.PREEMPTED
    assert planner.cancels == 1
    assert ("INFO", "Cancelled active action goal.") in [(e.level.name, e.message) for e in logs]


def test_failed_plan_goes_to_failed(aliases):
    from example_flexbe_states.example_behaviors import PlanAndFollowSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    from flex_nav.msg import GetPathResult  # noqa: PLC0415

    ctx, logs = context()
    executor = BehaviorExecutor(build_behavior(PlanAndFollowSM, context=ctx), context=ctx, inputs={"goal": "pose"})
    executor.run(timeout_s=1.0, stop_on_timeout=False)
    ctx.proxies.action_clients["get_path"].finish(ABORTED, GetPathResult(code=GetPathResult.EMPTY, message="no path"))
    result = executor.run(timeout_s=1.0)
    assert result.status is BehaviorStatus.FINISHED and result.outcome == "failed"
    assert ("WARN", "GetPath failed: no path") in [(e.level.name, e.message) for e in logs]


# --- ProxyServiceCaller --------------------------------------------------------------------------------------------
def test_service_caller_call_and_missing_service():
    hub = FakeHub()
    hub.service_handlers["/double"] = lambda request: request * 2
    ctx, logs = context(hub=hub)
    with using_context(ctx):
        from flex_nav.compat.flexbe_core.proxy import ProxyServiceCaller  # noqa: PLC0415

        caller = ProxyServiceCaller({"/double": int}, wait_duration=2)
        assert caller.is_available("/double")
        assert caller.call("/double", 21) == 42
        caller.setupService("/absent", int, wait_duration=1)
        assert not caller.is_available("/absent")
        with pytest.raises(NotReadyError, match="/absent is not available"):
            caller.call("/absent", 1)
        with pytest.raises(NotReadyError, match=r"service '/unknown' is not set up.*set up: /double, /absent"):
            caller.call("/unknown", 1)
    assert [(e.level.name, e.message) for e in logs] == [
        ("ERROR", "Service client /absent timed out: no service after 1.0 s")
    ]
