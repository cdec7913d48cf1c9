"""Which behavior's connections a FlexBE proxy uses, and what it needs from them.

FlexBE's proxies keep their publishers, subscribers and clients in class-level dicts: one set per
process, shared by every behavior. Here a proxy object uses the connection hub of ONE behavior: the
``proxies`` of the behavior context current when the proxy was created (states build their proxies in
``__init__``, which :func:`flex_nav.compat.flexbe_core.build_behavior` runs inside the behavior's
context), or, if there was none, the context running when the proxy is first used. Within that
behavior the hub shares connections by name (two states asking for the same topic get one
subscriber); two behaviors never share anything.

The hub is what the ROS runner injects as ``BehaviorContext.proxies``:
:class:`flex_nav.ros.proxies.RosProxies`. The FlexBE proxies use it through the same protocols as the
state library, :class:`flex_nav.behavior.proxies.Proxies` and its ``*Like`` connections (pure unit tests
inject fakes).
"""

from __future__ import annotations

from typing import Callable, Iterable, List, Optional, TypeVar

from flex_nav.behavior.context import current_context
from flex_nav.behavior.proxies import Proxies
from flex_nav.exceptions import NotReadyError

C = TypeVar("C")


class Binding:
    """The hub of one FlexBE proxy object, with the setup calls made before a hub was known."""

    __slots__ = ("_hub", "_owner", "_pending", "_set_up_as", "_set_up_by")

    def __init__(self, owner: str, *, set_up_by: str, set_up_as: str = "set up") -> None:
        """``owner``: the proxy's class name; ``set_up_by``: its method that sets a connection up, ``set_up_as``:
        what that did, in the past tense (for :meth:`require`'s message)."""
        self._owner = owner
        self._set_up_by = set_up_by
        self._set_up_as = set_up_as
        self._hub: Optional[Proxies] = self._current_hub()
        self._pending: List[Callable[[Proxies], None]] = []

    @staticmethod
    def _current_hub() -> Optional[Proxies]:
        ctx = current_context()
        return ctx.proxies if ctx is not None else None

    @property
    def bound(self) -> bool:
        return self._hub is not None

    def setup(self, action: Callable[[Proxies], None]) -> None:
        """Run ``action(hub)`` now if a hub is known, else when the proxy is first used in a running behavior."""
        hub = self._hub if self._hub is not None else self._bind()
        if hub is None:
            self._pending.append(action)
        else:
            action(hub)

    def peek(self) -> Optional[Proxies]:
        """The hub if one is known or a running behavior provides one now, else None (never raises)."""
        return self._hub if self._hub is not None else self._bind()

    def hub(self) -> Proxies:
        """The hub, binding to the running behavior's on first use; NotReadyError outside any behavior."""
        hub = self._hub if self._hub is not None else self._bind()
        if hub is None:
            raise NotReadyError(
                f"{self._owner} is used outside a behavior that has ROS proxies: create and use it while a "
                "flex_nav behavior runs (or is built) with proxies injected by its runner"
            )
        return hub

    def require(self, found: Optional[C], missing: str, set_up: Iterable[str]) -> C:
        """``found``, a connection looked up in the hub; NotReadyError when it is None, saying what is ``missing`` in
        this behavior, the call that sets it up and the names this proxy set up (``set_up``)."""
        if found is None:
            raise NotReadyError(
                f"{self._owner}: {missing} in this behavior; call {self._set_up_by}(topic, type) first "
                f"(this proxy {self._set_up_as}: {', '.join(set_up) or 'none'})"
            )
        return found

    def _bind(self) -> Optional[Proxies]:
        hub = self._current_hub()
        if hub is None:
            return None
        self._hub = hub
        pending, self._pending = self._pending, []
        for action in pending:
            action(hub)
        return hub


__all__ = ["Binding"]
