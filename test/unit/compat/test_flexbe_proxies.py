"""flexbe_core.proxy: FlexBE's method names on ONE process-wide set of connections, as in FlexBE (a FakeHub here)."""

from __future__ import annotations

from typing import List

import pytest
from unit.compat.compat_testlib import ABORTED, ACTIVE, PREEMPTED, SUCCEEDED

from flex_nav.behavior import Autonomy, BehaviorContext, BehaviorExecutor, BehaviorStatus, ManualClock
from flex_nav.behavior.events import LogEvent
from flex_nav.compat.flexbe_core.proxy.hub import process_proxies
from flex_nav.exceptions import NotReadyError


class Topic:
    """A message class (FakePublisher checks the type of what is published)."""

    def __init__(self, data=None):
        self.data = data


def context(name="test", hub=None):
    ctx = BehaviorContext(
        name, clock=ManualClock(), proxies=hub if hub is not None else process_proxies(), autonomy=Autonomy.FULL
    )
    logs: List[LogEvent] = []
    ctx.hooks.log.append(logs.append)
    return ctx, logs


# --- process-wide, as in FlexBE ----------------------------------------------------------------------------------
def test_two_behaviors_in_one_process_share_the_process_wide_connections(aliases, process_hub):
    from example_flexbe_states.example_behaviors import ExampleSM  # noqa: PLC0415
    from flexbe_core import build_behavior  # noqa: PLC0415

    first, _ = context("first")
    second, _ = context("second")
    first_behavior = build_behavior(ExampleSM, context=first, parameters={"limit": 1, "topic": "/shared"})
    second_behavior = build_behavior(ExampleSM, context=second, parameters={"limit": 2, "topic": "/shared"})
    first_run = BehaviorExecutor(first_behavior, context=first)
    second_run = BehaviorExecutor(second_behavior, context=second)
    for _ in range(200):  # interleaved in one thread
        first_run.spin_once()
        second_run.spin_once()
        first.clock.advance(0.1)
        second.clock.advance(0.1)
    assert first_run.status is BehaviorStatus.FINISHED and second_run.status is BehaviorStatus.FINISHED
    assert first_run.result().outputs["value"] == 1 and second_run.result().outputs["value"] == 2
    assert [m.data for m in process_hub.publishers["/shared"].sent] == ["hello", "hello"]  # one publisher


def test_proxies_work_outside_any_behavior_and_share_by_topic(aliases, process_hub):
    from example_flexbe_states.publish_string_state import PublishStringState  # noqa: PLC0415
    from flexbe_core.proxy import ProxyPublisher  # noqa: PLC0415
    from std_msgs.msg import String  # noqa: PLC0415

    PublishStringState(topic="/late")  # e.g. loaded offline, without any behavior
    assert ProxyPublisher().is_available("/late")  # another proxy object sees it: one set per process
    ProxyPublisher().publish("/late", String(data="direct"))
    assert [m.data for m in process_hub.publishers["/late"].sent] == ["direct"]


def test_publishing_on_a_topic_nobody_created_is_a_warning(aliases, caplog):
    from flexbe_core.proxy import ProxyPublisher  # noqa: PLC0415

    ProxyPublisher().publish("/x", Topic())
    assert "ProxyPublisher: topic /x not yet registered!" in caplog.text


# --- ProxyPublisher ----------------------------------------------------------------------------------------------
def test_publisher_publish_wait_for_any_and_unknown_topic(process_hub, caplog):
    from flex_nav.compat.flexbe_core.proxy import ProxyPublisher  # noqa: PLC0415

    pub = ProxyPublisher({"/a": Topic})
    other_state_pub = ProxyPublisher()  # another state, maybe of another behavior
    other_state_pub.publish("/a", Topic(1))
    pub.publish("/a", Topic(2))
    assert [m.data for m in process_hub.publishers["/a"].sent] == [1, 2]
    assert pub.is_available("/a") and not pub.is_available("/b")
    assert pub.wait_for_any("/a", timeout=0.05) is False  # nobody listens: the bounded wait runs out
    process_hub.publishers["/a"].connections = 1
    assert pub.wait_for_any("/a", timeout=5.0) is True
    assert pub.wait_for_any("/b", timeout=5.0) is False
    assert "Publisher /b not yet registered" in caplog.text


# --- ProxySubscriberCached ------------------------------------------------------------------------------------------
def test_subscriber_cache_buffer_and_callbacks(process_hub, caplog):
    from flex_nav.compat.flexbe_core.proxy import ProxySubscriberCached  # noqa: PLC0415

    received: List[Topic] = []
    sub = ProxySubscriberCached({"/cached": Topic})
    sub.subscribe("/buffered", Topic, callback=received.append, buffered=True)
    cached, buffered = process_hub.subscriptions["/cached"], process_hub.subscriptions["/buffered"]
    assert not sub.has_msg("/cached") and sub.get_last_msg("/cached") is None
    cached.inject(Topic("a"))
    assert ProxySubscriberCached().has_msg("/cached")  # the cache is the process's
    assert sub.get_last_msg("/cached").data == "a"
    sub.remove_last_msg("/cached")
    assert not sub.has_msg("/cached")
    sub._callback(Topic("injected"), "/cached")  # FlexBE's way of injecting a message
    assert sub.get_last_msg("/cached").data == "injected"
    for value in (1, 2, 3):
        buffered.inject(Topic(value))
    assert [m.data for m in received] == [1, 2, 3]
    assert sub.has_buffered("/buffered")
    assert sub.get_from_buffer("/buffered").data == 1
    sub.remove_last_msg("/buffered", clear_buffer=True)
    assert not sub.has_buffered("/buffered") and not sub.has_msg("/buffered")
    assert sub.get_from_buffer("/buffered") is None
    sub.make_persistant("/cached")
    sub.remove_last_msg("/cached")
    assert sub.has_msg("/cached")  # persistent: only replaced by newer messages
    sub.disable_buffer("/buffered")
    buffered.inject(Topic(5))
    assert not sub.has_buffered("/buffered") and sub.get_from_buffer("/buffered") is None
    assert "non-buffered topic" in caplog.text
    sub.unsubscribe_topic("/buffered")  # gone for every proxy of the process, callbacks included
    buffered.inject(Topic(6))
    assert len(received) == 4 and not sub.is_available("/buffered") and not sub.has_msg("/buffered")
    assert sub.get_last_msg("/nope") is None and "topic /nope is not subscribed" in caplog.text


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
def test_action_client_goal_result_feedback_cancel(process_hub):
    from flex_nav.compat.flexbe_core.proxy import ProxyActionClient  # noqa: PLC0415

    client = ProxyActionClient({"/move": Topic}, wait_duration=3)
    fake = process_hub.action_clients["/move"]
    assert fake.availability_waits == [3.0]  # setupClient waited (bounded) for the server
    assert client.is_available("/move") and not client.is_available("/other")
    ProxyActionClient().send_goal("/move", "goal-1")  # any proxy object of the process reaches the client
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
    with pytest.raises(NotReadyError, match=r"action '/other' is not set up.*set up in this process: /move"):
        client.send_goal("/other", "goal")


def test_action_client_without_server_logs_at_setup_and_fails_loudly_on_send(process_hub, caplog):
    from flex_nav.compat.flexbe_core.proxy import ProxyActionClient  # noqa: PLC0415

    process_hub.servers_up = False
    client = ProxyActionClient({"/move": Topic}, wait_duration=1)
    assert not client.is_available("/move")
    with pytest.raises(NotReadyError, match="/move is not available"):
        client.send_goal("/move", "goal")
    assert "Action client /move timed out: no server after 1.0 s" in caplog.text


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
def test_service_caller_call_and_missing_service(process_hub, caplog):
    from flex_nav.compat.flexbe_core.proxy import ProxyServiceCaller  # noqa: PLC0415

    process_hub.service_handlers["/double"] = lambda request: request * 2
    caller = ProxyServiceCaller({"/double": int}, wait_duration=2)
    assert caller.is_available("/double")
    assert ProxyServiceCaller().call("/double", 21) == 42
    caller.setupService("/absent", int, wait_duration=1)
    assert not caller.is_available("/absent")
    with pytest.raises(NotReadyError, match="/absent is not available"):
        caller.call("/absent", 1)
    with pytest.raises(
        NotReadyError, match=r"service '/unknown' is not set up.*set up in this process: /double, /absent"
    ):
        caller.call("/unknown", 1)
    assert "Service client /absent timed out: no service after 1.0 s" in caplog.text
