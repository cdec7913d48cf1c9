"""SMACH userdata: :class:`UserData` (a container's key/value store) and :class:`Remapper` (a state's view).

Every SMACH container owns a :class:`UserData` (``container.userdata``; its dict is ``_data``, which
smach_ros's introspection reads and replaces). A state's ``execute(ud)`` receives a :class:`Remapper`
on it that exposes only the keys the state declares, under the state's own names (``remapping`` maps
state key -> container key):

- reading a key that is not an input (or io) key raises :class:`InvalidUserCodeError` naming the
  declared inputs; writing a key that is not an output key raises the same (SMACH only logs there,
  which hides the bug);
- an input-only value comes back read-only, as SMACH's ``Const`` wrapper intends, through flex_nav's
  zero-copy views (:func:`flex_nav.behavior.readonly`): ROS messages, lists and dicts included;
- a missing key raises :class:`~flex_nav.exceptions.UserDataKeyError` (both a ``KeyError``, as in
  SMACH, and an ``AttributeError``, so ``hasattr`` and ``getattr(ud, k, default)`` work).
"""

from __future__ import annotations

import copy
import types
from typing import Any, Collection, Dict, Iterator, List, Mapping, Optional

from flex_nav.behavior.userdata import readonly
from flex_nav.exceptions import InvalidStateError, InvalidUserCodeError, UserDataKeyError


def _listed(values: Collection[str]) -> str:
    return ", ".join(sorted(values)) if values else "none"


class UserData:
    """SMACH's userdata structure: keys as attributes or items, stored in the dict ``_data``."""

    __slots__ = ("_data",)

    def __init__(self) -> None:
        object.__setattr__(self, "_data", {})

    def update(self, other_userdata: Any) -> None:
        """Copy every key of another UserData (or mapping) into this one, overwriting duplicates."""
        data = other_userdata._data if isinstance(other_userdata, UserData) else other_userdata
        self._data.update(data)

    def extract(self, keys: Collection[str], remapping: Mapping[str, str]) -> UserData:
        """A new UserData with shallow copies of ``keys``, each named back through ``remapping`` (local -> here)."""
        reverse = {target: local for local, target in remapping.items()}
        ud = UserData()
        for key in keys:
            ud._data[reverse.get(key, key)] = copy.copy(self[key])
        return ud

    def merge(self, ud: Any, keys: Collection[str], remapping: Mapping[str, str]) -> None:
        """Store shallow copies of ``ud``'s ``keys`` here, each under ``remapping.get(key, key)``."""
        for key in keys:
            self._data[remapping.get(key, key)] = copy.copy(ud[key])

    def keys(self) -> List[str]:
        return list(self._data)

    def __contains__(self, key: object) -> bool:
        return key in self._data

    def __iter__(self) -> Iterator[str]:
        return iter(list(self._data))

    def __len__(self) -> int:
        return len(self._data)

    def __getitem__(self, key: str) -> Any:
        try:
            return self._data[key]
        except KeyError:
            raise UserDataKeyError(f"SMACH userdata has no key {key!r} (keys: {_listed(self._data)})") from None

    def __setitem__(self, key: str, value: Any) -> None:
        self._data[key] = value

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        return self[name]

    def __setattr__(self, name: str, value: Any) -> None:
        if name.startswith("_"):
            object.__setattr__(self, name, value)
        else:
            self._data[name] = value

    def __repr__(self) -> str:
        return f"<UserData keys={sorted(self._data)}>"


_NO_REMAPPING: Mapping[str, str] = types.MappingProxyType({})
_COLLECTIONS = (tuple, list, frozenset, set)


class Remapper:
    """A state's view on its container's userdata: declared keys only, renamed by ``remapping``.

    ``ud`` is a :class:`UserData`, another Remapper (nested containers) or any mapping;
    ``remapping`` maps the state's key names to the container's (SMACH code sometimes passes ``[]``
    for "no remapping"; any empty value is accepted).
    """

    __slots__ = ("_input", "_map", "_output", "_ud")

    def __init__(
        self,
        ud: Any,
        input_keys: Collection[str] = (),
        output_keys: Collection[str] = (),
        remapping: Optional[Mapping[str, str]] = None,
    ) -> None:
        if remapping and not isinstance(remapping, Mapping):
            raise InvalidUserCodeError(f"remapping must be a mapping of state key -> container key, got {remapping!r}")
        # kept as given (not copied: a view is built for every state execution); never mutated here
        object.__setattr__(self, "_ud", ud)
        object.__setattr__(self, "_input", input_keys if type(input_keys) in _COLLECTIONS else tuple(input_keys))
        object.__setattr__(self, "_output", output_keys if type(output_keys) in _COLLECTIONS else tuple(output_keys))
        object.__setattr__(self, "_map", remapping if remapping else _NO_REMAPPING)

    def _remap(self, key: str) -> str:
        return str(self._map.get(key, key))

    def _read(self, key: str) -> Any:
        if key not in self._input:
            raise InvalidUserCodeError(
                f"reading SMACH userdata key {key!r}, but the state declares as input only: {_listed(self._input)} "
                "(declare it in input_keys or io_keys)"
            )
        target = self._map.get(key, key)
        try:
            value = self._ud[target]
        except KeyError:
            renamed = f" (remapped to {target!r})" if target != key else ""
            raise UserDataKeyError(f"SMACH userdata key {key!r}{renamed} has no value yet") from None
        return value if key in self._output else readonly(value)

    def _write(self, key: str, value: Any) -> None:
        if key not in self._output:
            raise InvalidUserCodeError(
                f"writing SMACH userdata key {key!r}, but the state declares as output only: {_listed(self._output)} "
                "(declare it in output_keys or io_keys)"
            )
        self._ud[self._map.get(key, key)] = value

    def __getitem__(self, key: str) -> Any:
        return self._read(key)

    def __setitem__(self, key: str, value: Any) -> None:
        self._write(key, value)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        return self._read(name)

    def __setattr__(self, name: str, value: Any) -> None:
        if name.startswith("_"):
            raise AttributeError(f"cannot set {name!r} on a SMACH userdata view")
        self._write(name, value)

    def __contains__(self, key: object) -> bool:
        return isinstance(key, str) and key in self._input and self._map.get(key, key) in self._ud

    def keys(self) -> List[str]:
        """The declared input keys that have a value (the state's names)."""
        return [key for key in sorted(self._input) if self._map.get(key, key) in self._ud]

    def update(self, other_userdata: Any) -> None:
        self._ud.update(other_userdata)

    def __repr__(self) -> str:
        return f"<Remapper inputs={sorted(self._input)} outputs={sorted(self._output)} remapping={dict(self._map)}>"


def remapping_of(remapping: Any, owner: str) -> Dict[str, str]:
    """Validated copy of a container-side remapping argument (None or empty -> {})."""
    if not remapping:
        return {}
    if not isinstance(remapping, Mapping):
        raise InvalidStateError(f"{owner}: remapping must map state keys to container keys, got {remapping!r}")
    for key, target in remapping.items():
        if not isinstance(key, str) or not isinstance(target, str) or not key or not target:
            raise InvalidStateError(f"{owner}: remapping {key!r} -> {target!r} must map a key name to a key name")
    return dict(remapping)


__all__ = ["Remapper", "UserData"]
