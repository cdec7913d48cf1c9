"""flex_nav.compat: SMACH's and FlexBE's Python APIs on top of flex_nav (rospy only once FlexBE's proxies reach ROS).

- :mod:`flex_nav.compat.smach` -- SMACH's API with SMACH's semantics (blocking ``execute``, threads in
  ``Concurrence``), for code written against ``import smach`` (and ``smach_ros`` on top of it).
- :mod:`flex_nav.compat.smach_adapter` -- :class:`~flex_nav.compat.smach_adapter.SmachStateAdapter`, a
  flex_nav state that runs a SMACH state (its blocking ``execute`` in one worker thread per activation).
- :mod:`flex_nav.compat.flexbe_core` -- flexbe_core 1.x's API (``EventState``, ``Behavior``,
  ``OperatableStateMachine``, proxies, ``Logger``...) mapped onto flex_nav's engine, so FlexBE state
  libraries and generated behaviors run unmodified in :class:`~flex_nav.behavior.BehaviorExecutor`, and
  FlexBE code that drives them itself (direct ``execute()``) gets FlexBE's semantics.
- :mod:`flex_nav.compat.flexbe_testing` -- FlexBE's Tester with its YAML test cases, on that ``flexbe_core``.

:func:`install_aliases` makes ``import smach`` / ``flexbe_core`` / ``flexbe_testing`` resolve to these packages when
the real ones are not installed (a runner calls it once, before importing state libraries).
"""

from __future__ import annotations

import importlib
import importlib.util
import pkgutil
import sys
from types import ModuleType
from typing import Dict, Sequence

from flex_nav.exceptions import ConfigError, choices_message

# top-level name a library imports -> the flex_nav package that provides it
ALIASES: Dict[str, str] = {
    "smach": "flex_nav.compat.smach",
    "flexbe_core": "flex_nav.compat.flexbe_core",
    "flexbe_testing": "flex_nav.compat.flexbe_testing",
}


def install_aliases(names: Sequence[str] = tuple(ALIASES)) -> Dict[str, str]:
    """Register ``smach`` / ``flexbe_core`` (and every submodule) in ``sys.modules`` unless the real package exists.

    Returns, per name, ``"flex_nav"`` (the alias is in place, now or from an earlier call) or
    ``"real"`` (the real package is installed or already imported, so it is left alone). Submodules are
    registered too (``smach.state``, ``flexbe_core.proxy``, ...), so that ``import smach.container`` or
    ``from flexbe_core.proxy import ProxyActionClient`` give the same module objects as the package.
    """
    report: Dict[str, str] = {}
    for name in names:
        if name not in ALIASES:
            raise ConfigError(choices_message("compatibility alias", name, ALIASES))
        target = ALIASES[name]
        existing = sys.modules.get(name)
        if existing is not None:
            report[name] = "flex_nav" if existing.__name__ == target else "real"
            continue
        if importlib.util.find_spec(name) is not None:
            report[name] = "real"
            continue
        package = importlib.import_module(target)
        modules: Dict[str, ModuleType] = {name: package}
        for info in pkgutil.walk_packages(package.__path__, prefix=target + "."):
            modules[name + info.name[len(target) :]] = importlib.import_module(info.name)
        sys.modules.update(modules)
        report[name] = "flex_nav"
    return report


def remove_aliases(names: Sequence[str] = tuple(ALIASES)) -> None:
    """Undo :func:`install_aliases` (only entries that point at flex_nav's modules are removed)."""
    for name in names:
        target = ALIASES[name]
        for key in [k for k in sys.modules if k == name or k.startswith(name + ".")]:
            module = sys.modules[key]
            if module.__name__ == target or module.__name__.startswith(target + "."):
                del sys.modules[key]


__all__ = ["ALIASES", "install_aliases", "remove_aliases"]
