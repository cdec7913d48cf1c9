"""A node's lockstep participant (no master): its hold name comes from the component's private namespace or is
given whole, exactly one of the two; with lockstep off it advertises nothing and every method does nothing."""

import pytest
import rospy

from flex_nav.ros.lockstep import (
    LockstepParticipant,
    accept_hold_name,
    accept_hold_param,
    lockstep_enabled,
    server_accept_hold,
)
from flex_nav.ros.private_ns import hosted_as
from flex_nav.testing.private_master import free_port


def test_the_name_is_the_components_namespace_and_what_it_holds_for() -> None:
    with hosted_as("get_path_server") as namespace:
        participant = LockstepParticipant("planning", enabled=False)
    assert participant.name == namespace + "/planning"


def test_a_whole_name_is_taken_as_given() -> None:
    participant = LockstepParticipant(name=accept_hold_name("/robot1/follow_path"), enabled=False)
    assert participant.name == "/robot1/follow_path/accept"


@pytest.mark.parametrize("what, name", [("", None), ("planning", "/robot1/planning")])
def test_neither_or_both_names_are_refused_with_the_values(what: str, name: object) -> None:
    with pytest.raises(ValueError, match="exactly one") as raised:
        LockstepParticipant(what, enabled=False, name=name)  # type: ignore[arg-type]
    assert repr(what) in str(raised.value) and repr(name) in str(raised.value)


def test_with_lockstep_off_nothing_is_advertised_and_every_call_is_a_no_op() -> None:
    participant = LockstepParticipant("control", enabled=False)
    assert participant.wait_connected(0.0)  # at once: nobody needs to listen
    participant.hold_clock(1.0)
    participant.hold_topic("/robot1/scan", 1.0)
    participant.release()
    assert participant._publisher is None


def test_a_server_without_lockstep_does_not_tell_its_clients_to_hold() -> None:
    # without a node, lockstep is off (wall clock): the parameter stays unset (no master is asked for it)
    accept = server_accept_hold("/robot1/get_path")
    assert not accept.enabled
    assert accept.name == "/robot1/get_path/accept"
    assert accept_hold_param("/robot1/get_path") == "/robot1/get_path/lockstep_accepts"


def test_a_node_whose_master_is_gone_runs_without_lockstep(monkeypatch: pytest.MonkeyPatch) -> None:
    # as in one test process after a system test's node and master: simulated time, a node, nobody to ask
    monkeypatch.setattr(rospy.rostime, "is_wallclock", lambda: False)
    monkeypatch.setattr(rospy.core, "is_initialized", lambda: True)
    monkeypatch.setenv("ROS_MASTER_URI", f"http://127.0.0.1:{free_port()}/")
    monkeypatch.setattr(rospy.core, "_master_proxy", None, raising=False)
    assert lockstep_enabled() is False
