"""flexbe_core.core.user_data: FlexBE's ``UserData``, the store and views of a directly executed FlexBE state machine.

Used when FlexBE code drives states itself (``state.execute(userdata)``, ``sm.execute(None)``, flexbe_testing's
Tester); a behavior run by flex_nav's executor uses the engine's userdata views instead. The semantics are
FlexBE 1.x's:

- ``UserData()`` is a free-standing store: any key may be read (if it has a value) or written.
- ``UserData(reference=parent, input_keys=[...], output_keys=[...], remap={...})`` is a state's view on its
  container's data: reading needs an input key (looked up as ``remap.get(key, key)`` in ``parent``), writing needs
  an output key (written through to ``parent``); a key the state writes is read back from the view. A view on a
  view reaches the container above (how a nested state machine reads its parent's data).
- Used as a context manager (``with UserData(...) as ud:``), leaving the block raises :class:`UserDataError` if a
  value read through an input-only key was modified in place (FlexBE compares ``repr()`` before and after; this is
  the direct-execution path only, never the engine's).
- ``ud(reference=..., add_from=..., update_from=..., remove_key=...)`` re-targets the view and merges local data.

Missing or undeclared keys raise :class:`UserDataError` (a :class:`~flex_nav.exceptions.FlexBEUserDataError`) whose
message names the key and what to declare.
"""

from __future__ import annotations

import copy
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional

from flex_nav.compat.flexbe_core.core.exceptions import UserDataError


def _fingerprint(value: Any) -> int:
    return hash(repr(value))


class UserData:
    """FlexBE's userdata store / state view (see the module docstring)."""

    def __init__(
        self,
        reference: Optional[Any] = None,
        input_keys: Optional[Iterable[str]] = None,
        output_keys: Optional[Iterable[str]] = None,
        remap: Optional[Mapping[str, str]] = None,
    ) -> None:
        self._data: Dict[str, Any] = {}
        self._reference: Any = reference if reference is not None else {}
        self._input_keys: Optional[List[str]] = list(input_keys) if input_keys is not None else None
        self._output_keys: Optional[List[str]] = list(output_keys) if output_keys is not None else None
        self._remap: Dict[str, str] = dict(remap or {})
        self._hashes: Dict[str, int] = {}

    # --- the input-only check -------------------------------------------------------------------
    def __enter__(self) -> UserData:
        return self

    def __exit__(self, *_exc: Any) -> None:
        for key, fingerprint in self._hashes.items():
            if fingerprint != _fingerprint(self._data[key]):
                raise UserDataError(f"Illegally modified input-only key '{key}', declare it as output.")

    # --- access -------------------------------------------------------------------------------------
    def __contains__(self, key: object) -> bool:
        if key in self._data:
            return True
        if self._input_keys is not None and key not in self._input_keys:
            return False
        return str(self._remap.get(str(key), str(key))) in self._reference

    def __getitem__(self, key: str) -> Any:
        if key in self._data and self._remap.get(key, key) not in self._reference:
            return self._data[key]
        if key not in self:
            if self._input_keys is not None and key not in self._input_keys:
                raise UserDataError(f"Key '{key}' cannot be accessed, declare it as input key for read access.")
            raise UserDataError(f"No data found for key '{key}'")
        value = self._reference[self._remap.get(key, key)]
        if self._output_keys is not None and key not in self._output_keys:
            self._data[key] = value
            self._hashes[key] = _fingerprint(value)
            if getattr(type(value), "_has_header", False):
                # rospy stamps a message's header when it is published: hand out a copy, so that publishing an
                # input-only message is not taken for modifying it
                value = copy.deepcopy(value)
        return value

    def __setitem__(self, key: str, value: Any) -> None:
        if self._output_keys is not None and key in self._output_keys:
            self._reference[self._remap.get(key, key)] = value
        self._data[key] = value

    def __getattr__(self, key: str) -> Any:
        if key.startswith("_"):
            raise AttributeError(key)
        return self[key]

    def __setattr__(self, key: str, value: Any) -> None:
        if key.startswith("_"):
            object.__setattr__(self, key, value)
            return
        if self._output_keys is not None and key not in self._output_keys:
            raise UserDataError(f"Key '{key}' cannot be set, declare it as output key for write access.")
        self[key] = value

    def __call__(
        self,
        reference: Optional[Any] = None,
        add_from: Optional[UserData] = None,
        update_from: Optional[UserData] = None,
        remove_key: Optional[str] = None,
    ) -> None:
        """Re-target to ``reference``; take the local data of ``add_from`` (missing keys only) and of
        ``update_from`` (all keys); drop the local ``remove_key``."""
        if reference is not None:
            self._reference = reference
        if isinstance(add_from, UserData):
            for key, value in add_from._data.items():
                self._data.setdefault(key, value)
        if isinstance(update_from, UserData):
            self._data.update(update_from._data)
        if remove_key is not None:
            self._data.pop(remove_key, None)

    # --- dict-like helpers (FlexBE code and flexbe_testing use these) ---------------------------------
    def keys(self) -> List[str]:
        """The keys with a value that this view may read (local data first)."""
        found = list(self._data)
        reference_keys = self._reference.keys() if hasattr(self._reference, "keys") else ()
        inverse = {target: key for key, target in self._remap.items()}
        for target in reference_keys:
            key = inverse.get(target, target)
            if key not in found and (self._input_keys is None or key in self._input_keys):
                found.append(key)
        return found

    def __iter__(self) -> Iterator[str]:
        return iter(self.keys())

    def get(self, key: str, default: Any = None) -> Any:
        return self[key] if key in self else default  # noqa: SIM401  (self is no dict)

    def update(self, other: Any) -> None:
        """Write every key of ``other`` (a mapping or a UserData) into this store."""
        items = other.items() if isinstance(other, Mapping) else ((k, other[k]) for k in other.keys())  # noqa: SIM118
        for key, value in list(items):
            self[key] = value

    def __len__(self) -> int:
        return len(self._data) + len(self._reference)

    def __str__(self) -> str:
        reference = self._reference
        reference_text = "\n  ".join(str(reference).split("\n")) if isinstance(reference, UserData) else str(reference)
        return (
            f"UserData object with {len(self)} data entries:\n"
            f"  Input Keys: {self._input_keys}\n  Output Keys: {self._output_keys}\n  Data: {self._data}\n"
            f"  Remapping: {self._remap}\n  Reference: {reference_text}"
        )

    __repr__ = __str__


__all__ = ["UserData"]
