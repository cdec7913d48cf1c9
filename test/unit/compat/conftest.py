"""Fixtures of the compatibility-layer tests."""

from __future__ import annotations

import importlib.util
import sys

import pytest
from unit.compat.compat_testlib import DATA_DIR, FakeHub

from flex_nav.compat import install_aliases, remove_aliases
from flex_nav.compat.flexbe_core.proxy.hub import reset_process_proxies, use_process_proxies

ALIASED = ("smach", "flexbe_core", "flexbe_testing")
LIBRARY = "example_flexbe_states"  # the FlexBE-idiom state library in test/data/compat


@pytest.fixture
def aliases():
    """``import smach`` / ``import flexbe_core`` resolve to flex_nav.compat during the test, then are restored.

    The project venv may hold the bench-only standalone-smach: it is hidden (``sys.modules[name] = None``
    is Python's way to block an import), so install_aliases sees SMACH as absent, as on a robot without it.
    Yields install_aliases' report and which names had a real package that was hidden.
    """
    roots = (*ALIASED, LIBRARY)
    saved = {k: v for k, v in sys.modules.items() if k.split(".")[0] in roots}
    for key in saved:
        del sys.modules[key]
    hidden = {}
    for name in ALIASED:
        hidden[name] = importlib.util.find_spec(name) is not None
        if hidden[name]:
            sys.modules[name] = None  # type: ignore[assignment]
    sys.path.insert(0, str(DATA_DIR))
    try:
        yield install_aliases(ALIASED), hidden
    finally:
        sys.path.remove(str(DATA_DIR))
        remove_aliases(ALIASED)
        for key in [k for k in sys.modules if k.split(".")[0] in roots]:
            del sys.modules[key]
        sys.modules.update(saved)


@pytest.fixture(autouse=True)
def process_hub():
    """The FlexBE proxies' process-wide connections (as in FlexBE), a FakeHub for the test, forgotten after it."""
    hub = FakeHub()
    use_process_proxies(hub)
    try:
        yield hub
    finally:
        reset_process_proxies()
