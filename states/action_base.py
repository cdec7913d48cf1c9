"""The common part of the action-client states: send a goal without blocking, map its result to an outcome.

:class:`ActionClientBase` does, for a subclass that builds the goal and names its outcomes:

- ``on_start``: gets the behavior's shared action client for ``action_name``;
- ``on_enter``: builds the goal from userdata (:meth:`make_goal`; a :class:`ConfigError` there fails the
  state with the reason);
- ``execute``: sends the goal as soon as the server is connected, polling without waiting; if it is not
  connected within ``server_timeout_s`` [s] after entry, logs it and returns the failure outcome. Then
  polls for the result and maps it (:meth:`map_result`): success needs the goal status SUCCEEDED *and* the
  result code SUCCESS (a cancelled goal's default result also reads code 0); other codes map through
  ``code_outcomes``; a goal ended without a result maps by its status. The server's reason
  (``result.message``) is logged with the outcome. A ``timeout_s`` > 0 bounds the goal's run time
  (cancelled, failure outcome); a server that goes away during the goal (disconnected for
  ``SERVER_LOST_S``) fails it too, so ``timeout_s`` 0 never means waiting for a dead server;
- ``on_exit``: cancels the goal if it is still active (preemption, a monitor ending a concurrency, a
  forced transition), so no server keeps driving for a state that is gone;
- ``on_pause``/``on_resume``: cancels the active goal (the robot must not drive on while the behavior is
  paused) and sends it again on resume.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Optional, Sequence

from actionlib_msgs.msg import GoalStatus

from flex_nav.action_types import ActionType
from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav_states import validation
from flex_nav_states.proxy_types import ActionClientLike, proxies_of

SEND_WAIT_S = 0.05  # [s] bound passed to send_goal once the server is known to be connected
SERVER_LOST_S = 2.0  # [s] a server disconnected this long during a goal has gone (a node restart takes longer)

GOAL_STATUS_NAMES = {
    getattr(GoalStatus, n): n
    for n in (
        "PENDING",
        "ACTIVE",
        "PREEMPTED",
        "SUCCEEDED",
        "ABORTED",
        "REJECTED",
        "PREEMPTING",
        "RECALLING",
        "RECALLED",
        "LOST",
    )
}
_CANCELLED_STATUSES = (GoalStatus.PREEMPTED, GoalStatus.RECALLED)


def status_name(status: int) -> str:
    return GOAL_STATUS_NAMES.get(status, f"UNKNOWN({status})")


class ServerLossWatch:
    """Tells when an action server has been disconnected for ``SERVER_LOST_S`` while a goal is out.

    Call :meth:`reset` when a goal is sent and :meth:`gone` on every tick while it runs; a reconnection
    within the grace starts the count again.
    """

    def __init__(self) -> None:
        self._lost_since_s: Optional[float] = None  # [s] since when the server is disconnected

    def reset(self) -> None:
        self._lost_since_s = None

    def gone(self, client: ActionClientLike, now_s: float) -> bool:
        """True once ``client``'s server has been disconnected for SERVER_LOST_S [s] without a break."""
        if client.is_available(0.0):
            self._lost_since_s = None
            return False
        if self._lost_since_s is None:
            self._lost_since_s = now_s
            return False
        return now_s - self._lost_since_s >= SERVER_LOST_S


@dataclass(frozen=True)
class ActionServer:
    """The action server a state sends its goals to, validated once, when built (a message names the state and its
    flat parameter): ``spec`` its action type, ``name`` (``action_name``: a legal ROS name, relative to the
    behavior's namespace), ``server_timeout_s`` [s] (> 0: how long after entry it may take to connect) and
    ``timeout_s`` [s] (>= 0: how long after sending a goal may run without result; 0: no limit)."""

    owner: str  # the state's class name, for messages
    spec: ActionType
    name: str
    server_timeout_s: float
    timeout_s: float

    def __post_init__(self) -> None:
        owner = self.owner
        validation.name(owner, "action_name", self.name)
        connect_s = validation.number(owner, "server_timeout_s", self.server_timeout_s, positive=True, unit="[s]")
        goal_s = validation.number(owner, "timeout_s", self.timeout_s, minimum=0.0, unit="[s]")
        object.__setattr__(self, "server_timeout_s", connect_s)  # ints made floats, in a frozen record
        object.__setattr__(self, "timeout_s", goal_s)


@dataclass(frozen=True)
class GoalOutcomes:
    """The state's outcome for the end of a goal: ``success`` (status SUCCEEDED and code SUCCESS), the outcome of
    each other result code by its name (``code_outcomes``), ``failure`` for anything else (no server, a timeout, a
    code not mapped) and ``cancelled`` for a goal cancelled by someone else (``failure`` when None)."""

    success: str
    failure: str
    code_outcomes: Mapping[str, str] = field(default_factory=dict)
    cancelled: Optional[str] = None


class ActionClientBase(State):
    """Base of the action-client states (not a state by itself; see the module docstring)."""

    def __init__(
        self,
        server: ActionServer,
        *,
        outcomes: Sequence[str],
        results: GoalOutcomes,
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
    ) -> None:
        super().__init__(outcomes=outcomes, input_keys=input_keys, output_keys=output_keys)
        spec = server.spec
        self._spec = spec
        self._action_name = server.name
        self._server_timeout_s = server.server_timeout_s
        self._timeout_s = server.timeout_s
        self._success = results.success
        self._failure = results.failure
        self._cancelled = results.cancelled if results.cancelled is not None else results.failure
        codes = spec.result_codes
        self._code_outcomes: Dict[int, str] = {}
        for code_name, outcome in results.code_outcomes.items():
            if code_name not in codes:
                raise ConfigError(
                    f"{server.owner}: {spec.name} has no result code {code_name} (codes: {', '.join(codes)})"
                )
            self._code_outcomes[codes[code_name]] = outcome
        self._success_code = codes["SUCCESS"]
        self._client: Optional[ActionClientLike] = None
        # per activation
        self._goal: Any = None
        self._error = ""
        self._sent = False
        self._done = False
        self._wait_start_s = 0.0  # [s] since when we wait for the server
        self._sent_s = 0.0  # [s] when the goal was sent
        self._server_loss = ServerLossWatch()  # the server disconnected during the goal
        self._paused_s = 0.0  # [s] goal run time spent paused (not counted against timeout_s)
        self._pause_start_s = 0.0

    # --- for subclasses --------------------------------------------------------------------------
    @property
    def action_name(self) -> str:
        return self._action_name

    @property
    def client(self) -> ActionClientLike:
        if self._client is None:
            self._client = proxies_of(self).action_client(self._action_name, self._spec.action)
        return self._client

    def make_goal(self, userdata: UserDataView) -> Any:
        """The goal message for this activation; raise ConfigError with the reason if userdata is unusable."""
        raise NotImplementedError

    def on_success(self, userdata: UserDataView, result: Any) -> str:
        """Write outputs from a successful result; returns the outcome (the success outcome by default)."""
        return self._success

    def describe_goal(self, goal: Any) -> str:
        """A short text for the log line when the goal is sent."""
        return ""

    # --- lifecycle -------------------------------------------------------------------------------
    def on_start(self) -> None:
        _ = self.client  # connect early: the server is usually up by the first entry

    def on_enter(self, userdata: UserDataView) -> None:
        self._goal, self._error = None, ""
        self._sent = self._done = False
        self._paused_s = 0.0
        self._wait_start_s = self.now_s()
        try:
            self._goal = self.make_goal(userdata)
        except ConfigError as err:
            self._error = str(err)

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if self._error:
            self.log_error(f"{self._action_name}: cannot send a goal: {self._error}")
            self._done = True
            return self._failure
        now = self.now_s()
        client = self.client
        if not self._sent and not self._try_send(client, now):
            waited_s = now - self._wait_start_s
            if waited_s >= self._server_timeout_s:
                self.log_error(
                    f"action server {self._action_name} ({self._spec.name}) is not available after "
                    f"{waited_s:.1f} s (server_timeout_s {self._server_timeout_s:g} s)"
                )
                self._done = True
                return self._failure
            return None
        if client.has_result():
            self._done = True
            return self.map_result(userdata, client.state(), client.result())
        problem = self._goal_problem(client, now)
        if problem is not None:
            self.log_error(problem)
            self._done = True
            return self._failure
        return None

    def on_exit(self, userdata: UserDataView) -> None:
        if self._sent and not self._done and self.client.is_active():
            self.client.cancel()
            self.log_info(f"{self._action_name}: goal cancelled (state left before the result)")

    def on_pause(self) -> None:
        self._pause_start_s = self.now_s()
        if self._sent and not self._done and self.client.is_active():
            self.client.cancel()
            self._sent = False  # send it again on resume
            self.log_info(f"{self._action_name}: goal cancelled while paused; it is sent again on resume")

    def on_resume(self, userdata: UserDataView) -> None:
        now = self.now_s()
        self._paused_s += now - self._pause_start_s
        if not self._sent:
            self._wait_start_s = now

    # --- internals -------------------------------------------------------------------------------
    def _goal_problem(self, client: ActionClientLike, now: float) -> Optional[str]:
        """Why the running goal has failed without a result (the server went away, timeout_s), else None."""
        if self._server_loss.gone(client, now):
            client.cancel()  # in case it was only cut off and comes back: it must not run the goal on
            return (f"action server {self._action_name} ({self._spec.name}) went away during the goal "
                    f"(disconnected for {SERVER_LOST_S:g} s; goal cancelled)")
        if self._timeout_s > 0.0 and now - self._sent_s - self._paused_s >= self._timeout_s:
            client.cancel()
            return f"{self._action_name}: no result within timeout_s {self._timeout_s:g} s; goal cancelled"
        return None

    def _try_send(self, client: ActionClientLike, now: float) -> bool:
        if not client.is_available(0.0):
            return False
        try:
            client.send_goal(self._goal, server_timeout_s=SEND_WAIT_S)
        except NotReadyError:  # disconnected between the two calls: try again next tick
            return False
        self._sent = True
        self._sent_s = now
        self._paused_s = 0.0
        self._server_loss.reset()
        what = self.describe_goal(self._goal)
        self.log_info(f"{self._action_name}: goal sent{': ' + what if what else ''}")
        return True

    def map_result(self, userdata: UserDataView, status: int, result: Any) -> str:
        """The outcome for a finished goal (see the module docstring), logging the server's reason."""
        reason = str(getattr(result, "message", "") or "no reason given") if result is not None else "no result"
        code = getattr(result, "code", None) if result is not None else None
        code_text = self._spec.code_name(code) if code is not None else "no result"
        where = f"{self._action_name}: {code_text} ({status_name(status)}): {reason}"
        if status == GoalStatus.SUCCEEDED and code == self._success_code:
            self.log_info(where)
            return self.on_success(userdata, result)
        if status in _CANCELLED_STATUSES:
            self.log_warn(where)
            return self._cancelled
        outcome = self._code_outcomes.get(code, self._failure) if code is not None else self._failure
        if outcome == self._success:  # a success code with a failed status: not a success
            outcome = self._failure
        if outcome == self._failure:
            self.log_error(where)
        else:
            self.log_warn(where)
        return outcome
