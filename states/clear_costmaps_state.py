"""ClearCostmapsState: clears several costmaps at once (one ClearCostmap goal per server), in bounded time."""

from __future__ import annotations

from typing import Dict, List, Optional, Sequence

from actionlib_msgs.msg import GoalStatus

from flex_nav.action_types import action_type
from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import NotReadyError
from flex_nav.msg import ClearCostmapGoal
from flex_nav_states import validation
from flex_nav_states.action_base import SEND_WAIT_S, status_name
from flex_nav_states.proxy_types import ActionClientLike, proxies_of

CLEAR_COSTMAP = action_type("ClearCostmap")


class ClearCostmapsState(State):
    """Clears several costmaps concurrently: one ClearCostmap goal to each server, all within a time bound.

    Each goal is sent as soon as its server is connected; the state ends when every server answered or when
    ``timeout_s`` has passed since entry, paused time excluded (unanswered goals are cancelled, missing
    servers are named). Clearing is harmless, so goals are not cancelled while the behavior is paused.

    -- costmaps   list   ClearCostmap action names (e.g. get_path_server/clear_costmap), at least one.
    -- timeout_s  float  [s] Bound on the whole state: server connection and all results.

    <= done    Every costmap was cleared (code SUCCESS from each server).
    <= failed  A server failed, was missing, or did not answer in time; each reason is logged.
    """

    def __init__(self, costmaps: Sequence[str] = ("get_path_server/clear_costmap",), timeout_s: float = 5.0) -> None:
        super().__init__(outcomes=["done", "failed"])
        owner = type(self).__name__
        self._names = validation.names(owner, "costmaps", costmaps, allow_empty=False)
        self._timeout_s = validation.number(owner, "timeout_s", timeout_s, positive=True, unit="[s]")
        self._clients: Dict[str, ActionClientLike] = {}
        self._sent: Dict[str, bool] = {}
        self._finished: Dict[str, bool] = {}
        self._problems: List[str] = []
        self._enter_s = 0.0
        self._pause_start_s = 0.0

    def on_start(self) -> None:
        proxies = proxies_of(self)
        self._clients = {n: proxies.action_client(n, CLEAR_COSTMAP.action) for n in self._names}

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()
        self._sent = dict.fromkeys(self._names, False)
        self._finished = dict.fromkeys(self._names, False)
        self._problems = []

    def execute(self, userdata: UserDataView) -> Optional[str]:
        for name, client in self._clients.items():
            if not self._sent[name]:
                self._try_send(name, client)
            elif not self._finished[name] and client.has_result():
                self._finished[name] = True
                self._check_result(name, client)
        if all(self._finished.values()):
            if self._problems:
                return "failed"
            self.log_info(f"cleared {len(self._names)} costmap(s): {', '.join(self._names)}")
            return "done"
        if self.now_s() - self._enter_s >= self._timeout_s:
            for name in self._names:
                if not self._sent[name]:
                    self._problem(f"action server {name} (ClearCostmap) is not available after {self._timeout_s:g} s")
                elif not self._finished[name]:
                    self._problem(f"{name}: no result within timeout_s {self._timeout_s:g} s; goal cancelled")
                    self._clients[name].cancel()
                    self._finished[name] = True
            return "failed"
        return None

    def on_pause(self) -> None:
        self._pause_start_s = self.now_s()

    def on_resume(self, userdata: UserDataView) -> None:
        self._enter_s += self.now_s() - self._pause_start_s  # paused time does not count against timeout_s

    def on_exit(self, userdata: UserDataView) -> None:
        for name, client in self._clients.items():
            if self._sent.get(name) and not self._finished.get(name) and client.is_active():
                client.cancel()
                self.log_info(f"{name}: goal cancelled (state left before the result)")

    def _try_send(self, name: str, client: ActionClientLike) -> None:
        if not client.is_available(0.0):
            return
        try:
            client.send_goal(ClearCostmapGoal(), server_timeout_s=SEND_WAIT_S)
        except NotReadyError:
            return
        self._sent[name] = True

    def _check_result(self, name: str, client: ActionClientLike) -> None:
        status, result = client.state(), client.result()
        code = getattr(result, "code", None) if result is not None else None
        reason = str(getattr(result, "message", "") or "no reason given") if result is not None else "no result"
        code_text = CLEAR_COSTMAP.code_name(code) if code is not None else "no result"
        where = f"{name}: {code_text} ({status_name(status)}): {reason}"
        if status == GoalStatus.SUCCEEDED and code == CLEAR_COSTMAP.result_codes["SUCCESS"]:
            self.log_info(where)
        else:
            self._problem(where)

    def _problem(self, text: str) -> None:
        self._problems.append(text)
        self.log_error(text)
