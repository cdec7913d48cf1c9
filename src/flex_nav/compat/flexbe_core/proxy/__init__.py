"""flexbe_core.proxy: FlexBE's ROS proxies, process-wide as in FlexBE (see :mod:`.hub`)."""

from flex_nav.compat.flexbe_core.proxy.hub import process_proxies, reset_process_proxies, use_process_proxies
from flex_nav.compat.flexbe_core.proxy.proxy_action_client import ProxyActionClient
from flex_nav.compat.flexbe_core.proxy.proxy_publisher import ProxyPublisher
from flex_nav.compat.flexbe_core.proxy.proxy_service_caller import ProxyServiceCaller
from flex_nav.compat.flexbe_core.proxy.proxy_subscriber_cached import ProxySubscriberCached

__all__ = [
    "ProxyActionClient",
    "ProxyPublisher",
    "ProxyServiceCaller",
    "ProxySubscriberCached",
    "process_proxies",
    "reset_process_proxies",
    "use_process_proxies",
]
