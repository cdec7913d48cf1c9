"""What states use of the behavior's proxies: the protocols of :mod:`flex_nav.behavior.proxies`, re-exported.

States are typed against these protocols, not against the ROS implementation
(:class:`flex_nav.ros.proxies.RosProxies`), so they import no rospy and run unchanged on the test double
:class:`flex_nav.testing.fake_proxies.FakeProxies`. :func:`proxies_of` fetches the proxies of the behavior a
state runs in (``NotReadyError`` if its runner injected none). ``ProxiesLike`` is the former name of
:class:`~flex_nav.behavior.proxies.Proxies`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from flex_nav.behavior.proxies import ActionClientLike, Proxies, PublisherLike, ServiceCallerLike, SubscriptionLike

if TYPE_CHECKING:
    from flex_nav.behavior.state import State

ProxiesLike = Proxies


def proxies_of(state: State) -> Proxies:
    """The proxies of the behavior ``state`` runs in."""
    return state.context.require_proxies()


__all__ = [
    "ActionClientLike",
    "Proxies",
    "ProxiesLike",
    "PublisherLike",
    "ServiceCallerLike",
    "SubscriptionLike",
    "proxies_of",
]
