"""SaveMapState: has the mapper write its map to files (its flex_nav/MapFile service, ``~save_map``)."""

from __future__ import annotations

from typing import Any, Optional

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.srv import MapFile, MapFileRequest
from flex_nav_states import validation
from flex_nav_states.background_work import BackgroundWork
from flex_nav_states.proxy_types import ServiceCallerLike, proxies_of


class SaveMapState(State):
    """Calls the mapper's save service (flex_nav/MapFile) and waits for its answer, off the behavior's thread.

    The mapper writes map_server's pair of files, ``<path>.yaml`` and ``<path>.pgm``, and answers ``ok`` with a
    message naming them, or not ok with the reason (a directory that is missing or not writable). The call waits
    at most ``server_timeout_s`` for the service to be there; the state gives up ``server_timeout_s + timeout_s``
    after entry if no answer has come (a call still running then is left to end on its own).

    -- service           str    flex_nav/MapFile service, relative to the behavior's namespace (the mapper's
                                ~save_map).
    -- path              str    Where to write, without extension; a relative path is taken from the mapper's
                                working directory (ROS_HOME).
    -- server_timeout_s  float  [s] Fail if the service is not there this long after entry (> 0).
    -- timeout_s         float  [s] Fail if it has not answered this much longer (> 0).

    <= saved   The mapper wrote the map; its message is logged.
    <= failed  The service is missing, failed, did not answer in time, or answered not ok; the reason is logged.
    """

    def __init__(self, service: str = "mapper/save_map", path: str = "map", server_timeout_s: float = 5.0,
                 timeout_s: float = 30.0) -> None:
        super().__init__(outcomes=["saved", "failed"])
        owner = type(self).__name__
        self._service = validation.name(owner, "service", service)
        self._path = validation.text(owner, "path", path)
        if not self._path.strip():
            raise ConfigError(f"{owner}: path must not be empty")
        self._server_timeout_s = validation.number(owner, "server_timeout_s", server_timeout_s, positive=True,
                                                   unit="[s]")
        self._timeout_s = validation.number(owner, "timeout_s", timeout_s, positive=True, unit="[s]")
        self._enter_s = 0.0
        self._caller: Optional[ServiceCallerLike] = None
        self._call: Optional[BackgroundWork[Any]] = None

    def on_start(self) -> None:
        self._caller = proxies_of(self).service_caller(self._service, MapFile)

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()
        caller = self._caller if self._caller is not None else proxies_of(self).service_caller(self._service, MapFile)
        request = MapFileRequest(path=self._path)
        wait_s = self._server_timeout_s
        self._call = BackgroundWork(f"call {self._service}", lambda: caller.call(request, timeout_s=wait_s))
        self.log_info(f"asking {self._service} to save the map to {self._path}")

    def on_exit(self, userdata: UserDataView) -> None:
        self._call = None  # a call still running ends on its own; its answer is dropped

    def execute(self, userdata: UserDataView) -> Optional[str]:
        call = self._call
        assert call is not None  # on_enter started it
        if not call.done():
            if self.now_s() - self._enter_s >= self._server_timeout_s + self._timeout_s:
                self.log_error(f"{self._service} did not answer within {self._server_timeout_s + self._timeout_s:g} s")
                return "failed"
            return None
        try:
            response = call.result()
        except Exception as err:  # the proxy's NotReadyError, or whatever the call raised
            self.log_error(f"could not save the map: {type(err).__name__}: {err}")
            return "failed"
        message = str(getattr(response, "message", ""))
        if not getattr(response, "ok", False):
            self.log_error(f"{self._service} did not save the map to {self._path}: {message or '(no reason given)'}")
            return "failed"
        self.log_info(f"map saved: {message or self._path}")
        return "saved"
