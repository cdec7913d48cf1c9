"""Constructor-time checks of state parameters: each error names the state, the parameter and the bad value.

A behavior file is validated when it is loaded (constructors run then), so a typo in a YAML parameter is
reported before the robot moves, never halfway through a run. The checks are :mod:`flex_nav.validation`'s
(one module for the whole package), re-exported here for the states and for user states; the parameter groups
the motion states share are in :mod:`flex_nav_states.motion_params`.
"""

from __future__ import annotations

from flex_nav.validation import boolean, choice, integer, name, names, number, text

__all__ = ["MAX_ANGULAR_RADPS", "MAX_LINEAR_MPS", "boolean", "choice", "integer", "name", "names", "number", "text"]

# Sanity bounds of the motion states' speed parameters: far above what the supported bases drive (0.3-0.7 m/s,
# 1.5-2 rad/s in config/), so a value beyond them is a unit mistake (cm/s, deg/s), refused at load time
# (the rule: flex_nav_states.motion_params.SpeedLimits).
MAX_LINEAR_MPS = 1.0  # [m/s]
MAX_ANGULAR_RADPS = 3.2  # [rad/s]
