"""FlexBE's Autonomy constants (plain ints, as in flexbe_core; flex_nav's engine accepts them)."""

from __future__ import annotations


class Autonomy:
    """Required autonomy of a transition: it fires by itself only when the behavior's autonomy is higher."""

    Inherit = 0  # FlexBE: rely on a level defined elsewhere (same value as Off)
    Off = 0  # fires at any autonomy above Off
    Low = 1
    High = 2
    Full = 3  # always needs the operator


__all__ = ["Autonomy"]
