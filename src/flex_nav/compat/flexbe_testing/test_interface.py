"""flexbe_testing.test_interface: imports, instantiates and executes the state or behavior under test, directly
(FlexBE's way), bounded by ``time_limit_s``."""

from __future__ import annotations

import importlib
import inspect
import time
from typing import Any, Callable, Dict, Optional

from flex_nav.compat.flexbe_core.behavior import Behavior
from flex_nav.compat.flexbe_core.core import EventState
from flex_nav.compat.flexbe_core.core.user_data import UserData
from flex_nav.compat.flexbe_testing.logger import Logger
from flex_nav.exceptions import ConfigError, TimedOutError, choices_message

DEFAULT_TIME_LIMIT_S = 30.0  # [s] longest execution of one test case


class TestInterface:
    """The class under test (a state or a behavior), by module path and class name."""

    __test__ = False  # not a pytest test class

    def __init__(self, path: str, classname: str) -> None:
        module = importlib.import_module(path)
        classes = {
            name: member
            for name, member in inspect.getmembers(module, inspect.isclass)
            if member.__module__ == module.__name__
        }
        if classname not in classes:
            raise ConfigError(choices_message(f"class in {path}", classname, classes))
        self._class = classes[classname]
        self._instance: Any = None
        Logger.print_positive(f"{self.get_base_name()} imported")

    def is_state(self) -> bool:
        return issubclass(self._class, EventState)

    def get_base_name(self) -> str:
        return "state" if self.is_state() else "behavior"

    def instantiate(self, params: Optional[Dict[str, Any]] = None) -> None:
        if self.is_state():
            self._instance = self._class(**(params or {}))
        else:
            if not issubclass(self._class, Behavior):
                raise ConfigError(f"{self._class.__name__} is neither a FlexBE EventState nor a Behavior")
            behavior = self._class()
            for name, value in (params or {}).items():
                behavior.set_parameter(name, value)
            behavior.set_up(id=0, autonomy_level=255, debug=False)
            self._instance = behavior
        Logger.print_positive(f"{self.get_base_name()} instantiated")

    def execute(
        self,
        userdata: UserData,
        spin_cb: Optional[Callable[[], None]] = None,
        time_limit_s: float = DEFAULT_TIME_LIMIT_S,
    ) -> Optional[str]:
        spin = spin_cb or (lambda: None)
        outcome = (
            self._execute_state(userdata, spin, time_limit_s)
            if self.is_state()
            else self._execute_behavior(userdata, spin, time_limit_s)
        )
        Logger.print_positive(f"finished {self.get_base_name()} execution")
        return outcome

    def _execute_state(self, userdata: UserData, spin: Callable[[], None], time_limit_s: float) -> Optional[str]:
        state = self._instance
        state.on_start()
        try:
            return _until_outcome(lambda: state.execute(userdata), state.sleep, spin, time_limit_s)
        finally:
            state.on_stop()

    def _execute_behavior(self, userdata: UserData, spin: Callable[[], None], time_limit_s: float) -> Optional[str]:
        behavior = self._instance
        behavior.prepare_for_execution(dict(userdata._data))
        behavior.confirm()
        machine = behavior._state_machine
        try:
            return _until_outcome(lambda: machine.execute(userdata), machine.sleep, spin, time_limit_s)
        finally:
            machine.destroy()


def _until_outcome(
    step: Callable[[], Optional[str]], sleep: Callable[[], None], spin: Callable[[], None], time_limit_s: float
) -> Optional[str]:
    deadline = time.monotonic() + time_limit_s
    while True:
        outcome = step()
        if outcome is not None:
            return outcome
        if time.monotonic() >= deadline:
            raise TimedOutError(f"no outcome within the time limit of {time_limit_s:g} s")
        sleep()
        spin()


__all__ = ["DEFAULT_TIME_LIMIT_S", "TestInterface"]
