"""flexbe_core.proxy: FlexBE's ROS proxies, bound to one behavior's connections (see :mod:`.hub`)."""

from flex_nav.compat.flexbe_core.proxy.proxy_action_client import ProxyActionClient
from flex_nav.compat.flexbe_core.proxy.proxy_publisher import ProxyPublisher
from flex_nav.compat.flexbe_core.proxy.proxy_service_caller import ProxyServiceCaller
from flex_nav.compat.flexbe_core.proxy.proxy_subscriber_cached import ProxySubscriberCached

__all__ = ["ProxyActionClient", "ProxyPublisher", "ProxyServiceCaller", "ProxySubscriberCached"]
