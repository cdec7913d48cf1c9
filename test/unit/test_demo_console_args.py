"""The demo's ``--console PORT`` and ``--hold`` without starting anything: the arguments, and the hold loop's
ends (a process of the stack exits, ROS shuts down, Ctrl-C)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, List

import pytest

from flex_nav.apps import nav_demo


class FakeProcess:
    def __init__(self, alive: List[bool]) -> None:
        self.argv = ["rosrun", "flex_nav", "console", "_port:=8080"]
        self.log_path = Path("console.log")
        self._alive = alive

    def running(self) -> bool:
        return self._alive.pop(0) if self._alive else False


def test_console_and_hold_are_parsed_and_a_bad_port_refused(capsys: pytest.CaptureFixture[str]) -> None:
    args = nav_demo.parse_args(["--console", "8090", "--hold"])
    assert args.console == 8090 and args.hold
    plain = nav_demo.parse_args([])
    assert plain.console == 0 and not plain.hold
    with pytest.raises(SystemExit):
        nav_demo.parse_args(["--console", "70000"])
    assert "--console 70000 is not a TCP port (1..65535)" in capsys.readouterr().err


def test_hold_ends_when_a_process_exits_ros_shuts_down_or_on_ctrl_c(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(nav_demo.time, "sleep", lambda _s: None)
    proc: Any = FakeProcess([True, True])
    assert nav_demo.hold([proc], lambda: False) == "rosrun flex_nav console _port:=8080 exited (log console.log)"
    lasting: Any = FakeProcess([True] * 10)
    assert nav_demo.hold([lasting], iter([False, True]).__next__) == "ROS shut down (Ctrl-C)"

    def interrupted() -> bool:
        raise KeyboardInterrupt

    assert nav_demo.hold([lasting], interrupted) == "Ctrl-C"
