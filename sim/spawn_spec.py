"""Which robots to spawn: the world's defaults, or a selection/override given as text or a list.

Text form (the ``_robots:=`` parameter of ``rosrun flex_nav sim``), entries separated by commas or
spaces, each one of::

    NAME                       a robot of the world's ``robots`` list, as defined there
    NAME:PROFILE               ... with another profile
    NAME:PROFILE:X:Y[:YAW_DEG] a robot anywhere ([m], [m], [deg])

List form (YAML): ``[{name: robot1, profile: kobuki, pose: [1.0, 2.0, 90]}, ...]``, where ``profile``
and ``pose`` may be left out for robots the world defines. Names become ROS namespaces and frame
prefixes; :func:`flex_nav_sim.world.check_spawns` rejects duplicates and overlaps later.
"""

from __future__ import annotations

import math
import re
from typing import Dict, List, Optional

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav_sim.world import Spawn, WorldSpec
from flex_nav_sim.yaml_fields import Fields

_SEPARATORS = re.compile(r"[,\s]+")


def resolve_spawns(world: WorldSpec, spec: object) -> List[Spawn]:
    """Spawns for ``spec`` (None or "" -> the world's own list); ConfigError names the bad entry."""
    if spec is None or spec in ("", []):
        return list(world.spawns)
    defaults = {s.name: s for s in world.spawns}
    if isinstance(spec, str):
        return [_from_text(entry, defaults, world) for entry in _SEPARATORS.split(spec.strip()) if entry]
    if isinstance(spec, list):
        return [_from_mapping(i, item, defaults, world) for i, item in enumerate(spec)]
    raise ConfigError(f"robots must be text (NAME[:PROFILE[:X:Y[:YAW_DEG]]], ...) or a list, got {spec!r}")


def _default(name: str, defaults: Dict[str, Spawn], world: WorldSpec, what: str) -> Spawn:
    if name not in defaults:
        raise ConfigError(
            choices_message(f"robots entry {what!r}: robot", name, list(defaults))
            + f" in world {world.name}; give a profile and a pose (NAME:PROFILE:X:Y[:YAW_DEG]) for a new robot"
        )
    return defaults[name]


def _from_text(entry: str, defaults: Dict[str, Spawn], world: WorldSpec) -> Spawn:
    parts = entry.split(":")
    name = parts[0]
    if len(parts) == 1:
        return _default(name, defaults, world, entry)
    if len(parts) == 2:
        base = _default(name, defaults, world, entry)
        return Spawn(name, parts[1] or base.profile, base.pose)
    if len(parts) in (4, 5):
        try:
            numbers = [float(p) for p in parts[2:]]
        except ValueError:
            raise ConfigError(f"robots entry {entry!r}: X, Y and YAW_DEG must be numbers") from None
        if not all(math.isfinite(n) for n in numbers):
            raise ConfigError(f"robots entry {entry!r}: X, Y and YAW_DEG must be finite")
        yaw = math.radians(numbers[2]) if len(numbers) == 3 else 0.0
        return Spawn(name, parts[1], (numbers[0], numbers[1], yaw))
    raise ConfigError(f"robots entry {entry!r} is not NAME, NAME:PROFILE or NAME:PROFILE:X:Y[:YAW_DEG]")


def _from_mapping(index: int, item: object, defaults: Dict[str, Spawn], world: WorldSpec) -> Spawn:
    f = Fields(item, "robots parameter", f"robots[{index}]")
    f.raw("pose", None)  # a known field even when the world's pose is used
    name = f.string("name")
    base: Optional[Spawn] = defaults.get(name)
    if base is None and not (f.has("profile") and f.has("pose")):
        base = _default(name, defaults, world, name)  # raises, listing the world's robots
    profile = f.string("profile", base.profile if base else None)
    pose = f.pose("pose") if f.has("pose") or base is None else base.pose
    f.done()
    return Spawn(name, profile, pose)
