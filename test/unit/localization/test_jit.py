"""numba with a cache where one can be written, and without where none can (a read-only installation)."""

import numba.core.caching
import numpy as np

from flex_nav.localization.jit import cached_njit


def _double(values):
    return values * 2.0


def cache_kind(kernel) -> str:
    return type(getattr(kernel, "_cache", None)).__name__


def test_compiles_with_a_cache():
    kernel = cached_njit(_double)
    np.testing.assert_array_equal(kernel(np.arange(3.0)), [0.0, 2.0, 4.0])
    assert cache_kind(kernel) == "FunctionCache"


def test_nowhere_to_write_falls_back_to_no_cache(monkeypatch):
    # what numba does when neither __pycache__ beside the module nor its user-wide cache folder is writable
    monkeypatch.setattr(numba.core.caching.CacheImpl, "_locator_classes", [])
    kernel = cached_njit(_double)
    np.testing.assert_array_equal(kernel(np.arange(3.0)), [0.0, 2.0, 4.0])
    assert cache_kind(kernel) == "NullCache"
