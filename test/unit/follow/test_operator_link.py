"""OperatorLink: the operator side's heartbeat on wall time; lost after the timeout, and before the first one."""

from __future__ import annotations

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nav.control.operator_link import OperatorLink


def test_off_never_loses_the_link() -> None:
    link = OperatorLink(0.0)
    assert not link.enabled
    assert not link.lost(1e6)


def test_lost_before_the_first_heartbeat_and_after_the_timeout() -> None:
    link = OperatorLink(0.5)
    assert link.lost(0.0)
    assert "no operator heartbeat" in link.why_lost(0.0, "/r1/operator_heartbeat")
    link.heard(1.0)
    assert not link.lost(1.5)
    assert link.lost(1.51)
    assert "link to the operator lost: no heartbeat on /r1/operator_heartbeat for 0.51 s" in link.why_lost(
        1.51, "/r1/operator_heartbeat")
    link.heard(2.0)
    assert not link.lost(2.1)


@pytest.mark.parametrize("bad", [-1.0, float("nan")])
def test_bad_timeouts_are_refused(bad: float) -> None:
    with pytest.raises(ConfigError, match="heartbeat timeout"):
        OperatorLink(bad)
