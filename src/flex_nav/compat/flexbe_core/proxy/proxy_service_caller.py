"""FlexBE's ProxyServiceCaller: process-wide service callers by name (see :mod:`.hub`): ``setupService``,
``is_available``, ``call``."""

from __future__ import annotations

from typing import Any, ClassVar, Dict, Optional

from flex_nav.behavior.proxies import ServiceCallerLike
from flex_nav.compat.flexbe_core.logger import Logger
from flex_nav.compat.flexbe_core.proxy.hub import on_reset, process_proxies
from flex_nav.exceptions import NotReadyError

CALL_SERVICE_WAIT_S = 1.0  # [s] longest wait for the service when calling it (setupService waited already)


class ProxyServiceCaller:
    """Service callers shared by the whole process (``ProxyServiceCaller({'/clear': Empty})``)."""

    _services: ClassVar[Dict[str, type]] = {}

    def __init__(self, topics: Optional[Dict[str, type]] = None, wait_duration: float = 10) -> None:
        for topic, msg_type in (topics or {}).items():
            self.setupService(topic, msg_type, wait_duration=wait_duration)

    def setupService(  # noqa: N802  (FlexBE's name)
        self, topic: str, msg_type: type, persistent: bool = False, wait_duration: float = 10
    ) -> None:
        """Create the caller (once per process); wait at most ``wait_duration`` [s] for the service (log if absent).

        ``persistent`` is accepted for FlexBE compatibility and ignored (connections are per call).
        """
        caller = process_proxies().service_caller(topic, msg_type)
        ProxyServiceCaller._services[topic] = msg_type
        if wait_duration > 0 and not caller.is_available(float(wait_duration)):
            Logger.logerr(f"Service client {topic} timed out: no service after {float(wait_duration):.1f} s")

    def is_available(self, topic: str) -> bool:
        if topic not in ProxyServiceCaller._services:
            return False
        caller = process_proxies().get_service_caller(topic)
        return caller is not None and bool(caller.is_available(0.0))

    def call(self, topic: str, request: Any) -> Any:
        """Call the service (blocks for the call; NotReadyError if it is absent or fails)."""
        return self._caller(topic).call(request, timeout_s=CALL_SERVICE_WAIT_S)

    def _caller(self, topic: str) -> ServiceCallerLike:
        caller = process_proxies().get_service_caller(topic) if topic in ProxyServiceCaller._services else None
        if caller is None:
            raise NotReadyError(
                f"ProxyServiceCaller: service {topic!r} is not set up; call setupService(topic, type) first "
                f"(set up in this process: {', '.join(ProxyServiceCaller._services) or 'none'})"
            )
        return caller


on_reset(ProxyServiceCaller._services.clear)

__all__ = ["ProxyServiceCaller"]
