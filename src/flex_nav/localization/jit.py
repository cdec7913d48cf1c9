"""numba's ``njit`` with an on-disk cache where one can be written, and without it where none can; and the choice
between the compiled kernels and their plain-numpy twins.

Where numba keeps the cache: ``__pycache__`` beside this package's modules when that folder is writable (a
checkout, an editable install), else numba's user-wide cache (``$NUMBA_CACHE_DIR`` if set, otherwise
``~/.cache/numba``). In a read-only installation with no writable home either, ``njit(cache=True)`` raises
``RuntimeError("cannot cache function ...")`` as the module is imported; :func:`cached_njit` then compiles the
kernel without a cache (a few seconds at the first call of each process) instead of failing the import.
"""

from __future__ import annotations

import enum
from typing import Any, Callable, TypeVar

from numba import njit

F = TypeVar("F", bound=Callable[..., Any])


def cached_njit(function: F) -> F:
    """``njit(cache=True, nogil=True)(function)``, or the same without ``cache`` if numba finds nowhere to write."""
    try:
        compiled = njit(cache=True, nogil=True)(function)
    except RuntimeError:  # "cannot cache function ...: no locator available": nowhere writable
        compiled = njit(nogil=True)(function)
    return compiled  # type: ignore[no-any-return]


class Kernel(enum.Enum):
    """Which implementation of the hot loops a filter runs: the numba-compiled one, or the plain-numpy twin with the
    same maths (the reference of the benchmark and of the tests)."""

    NUMBA = "numba"
    NUMPY = "numpy"
