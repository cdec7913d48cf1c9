"""FlexBE's ProxyServiceCaller on the behavior's connection hub: ``setupService``, ``is_available``, ``call``."""

from __future__ import annotations

from typing import Any, Dict, Optional

from flex_nav.behavior.proxies import Proxies, ServiceCallerLike
from flex_nav.compat.flexbe_core.logger import Logger
from flex_nav.compat.flexbe_core.proxy.hub import Binding

CALL_SERVICE_WAIT_S = 1.0  # [s] longest wait for the service when calling it (setupService waited already)


class ProxyServiceCaller:
    """Service callers of the current behavior, by service name (``ProxyServiceCaller({'/clear': Empty})``)."""

    def __init__(self, topics: Optional[Dict[str, type]] = None, wait_duration: float = 10) -> None:
        self._binding = Binding("ProxyServiceCaller", set_up_by="setupService")
        self._topics: Dict[str, type] = {}
        for topic, msg_type in (topics or {}).items():
            self.setupService(topic, msg_type, wait_duration=wait_duration)

    def setupService(  # noqa: N802  (FlexBE's name)
        self, topic: str, msg_type: type, persistent: bool = False, wait_duration: float = 10
    ) -> None:
        """Create the caller; wait at most ``wait_duration`` [s] for the service (log if absent).

        ``persistent`` is accepted for FlexBE compatibility and ignored (connections are per call).
        """
        self._topics[topic] = msg_type

        def create(hub: Proxies) -> None:
            caller = hub.service_caller(topic, msg_type)
            if wait_duration > 0 and not caller.is_available(float(wait_duration)):
                Logger.logerr(f"Service client {topic} timed out: no service after {float(wait_duration):.1f} s")

        self._binding.setup(create)

    def is_available(self, topic: str) -> bool:
        hub = self._binding.peek()
        if hub is None:
            return False
        caller = hub.get_service_caller(topic)
        return caller is not None and bool(caller.is_available(0.0))

    def call(self, topic: str, request: Any) -> Any:
        """Call the service (blocks for the call; NotReadyError if it is absent or fails)."""
        return self._caller(topic).call(request, timeout_s=CALL_SERVICE_WAIT_S)

    def _caller(self, topic: str) -> ServiceCallerLike:
        caller = self._binding.hub().get_service_caller(topic)
        return self._binding.require(caller, f"service {topic!r} is not set up", self._topics)


__all__ = ["ProxyServiceCaller"]
