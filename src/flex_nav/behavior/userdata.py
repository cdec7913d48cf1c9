"""Userdata: the keys a state declares, and read-only views that protect input-only values.

Each container owns a plain ``dict`` store. Every child gets one :class:`UserDataView` on it, built
once when the behavior is attached (not per transition), that:

- lets the child read only its ``input_keys`` and write only its ``output_keys``, under the child's
  own names (``remapping`` maps child key -> container key);
- raises :class:`~flex_nav.exceptions.UserDataKeyError` for an undeclared read or write (and for a
  read of a key that has no value yet) and :class:`~flex_nav.exceptions.ReadOnlyUserDataError` for a
  write to an input-only key;
- returns input-only values through :func:`readonly`, a zero-copy read-only proxy: a 1 MB message
  costs one small wrapper object per read, nothing per transition (no copy, no hashing).

Reading works as attribute or item: ``userdata.goal`` or ``userdata["goal"]``.

What :func:`readonly` protects: attribute and item assignment/deletion through the view, at any
depth (nested messages, lists, dicts, numpy arrays as non-writeable views); list/dict/set mutators
are absent from the views. What it cannot protect: methods of an arbitrary object that mutate it
internally (they are returned bound to the real object). ``isinstance(view, OriginalType)`` holds.
:func:`unwrap` gives the real object back when a library needs it (e.g. to put it in a message);
the caller then promises not to mutate it.
"""

from __future__ import annotations

import enum
import sys
import types
from typing import TYPE_CHECKING, AbstractSet, Any, Dict, Iterator, Mapping, Sequence, Tuple

from flex_nav.exceptions import ReadOnlyUserDataError, UserDataKeyError

if TYPE_CHECKING:
    from flex_nav.behavior.state import State

_IMMUTABLE_TYPES = frozenset({int, float, complex, str, bytes, bool, type(None), frozenset, range, type(Ellipsis)})
_CALLABLE_TYPES = (
    types.FunctionType,
    types.MethodType,
    types.BuiltinFunctionType,
    types.BuiltinMethodType,
    type,
    types.ModuleType,
)


def readonly(value: Any) -> Any:
    """Return ``value`` itself if immutable, else a read-only, zero-copy view of it."""
    kind = type(value)
    if kind in _IMMUTABLE_TYPES:
        return value
    if kind is list or kind is tuple:
        return ReadOnlySequence(value)
    if kind is dict:
        return ReadOnlyMapping(value)
    return _readonly_other(value)


def _readonly_other(value: Any) -> Any:  # noqa: PLR0911  (one return per kind of value)
    kind = type(value)
    if kind in _VIEW_TYPES:
        return value
    mro = kind.__mro__
    if _SPECIAL_BASES_SET.isdisjoint(mro):  # the common case: a message or other plain object
        numpy = sys.modules.get("numpy")  # a value can only be an ndarray if numpy is imported
        if numpy is not None and numpy.ndarray in mro:
            view = value.view()
            view.flags.writeable = False
            return view
        return ReadOnlyObject(value)
    if isinstance(value, _PASS_THROUGH):  # enums, callables, subclasses of immutable builtins
        return value
    if isinstance(value, tuple) and hasattr(value, "_fields"):  # a named tuple: keep its field attributes
        return ReadOnlyObject(value)
    if isinstance(value, (list, tuple)):
        return ReadOnlySequence(value)
    if isinstance(value, dict):
        return ReadOnlyMapping(value)
    if isinstance(value, (set, frozenset)):
        return ReadOnlySet(value)
    return memoryview(value).toreadonly()  # bytearray, memoryview


def unwrap(value: Any) -> Any:
    """The real object behind a read-only view (identity for anything else). Breaks the protection."""
    if type(value) in _VIEW_TYPES:
        return object.__getattribute__(value, "_ro_target")
    return value


def _refuse(target: object, what: str) -> ReadOnlyUserDataError:
    return ReadOnlyUserDataError(
        f"cannot {what} on input-only userdata (a read-only view of {type(target).__name__}); "
        "declare the key as an output of the state to modify it"
    )


def _refusing(*names: str) -> Dict[str, Any]:
    """Methods that refuse the mutators of the wrapped container type with a clear error."""

    def make(name: str) -> Any:
        def refuse(self: Any, *args: Any, **kwargs: Any) -> Any:
            raise _refuse(object.__getattribute__(self, "_ro_target"), f"call {name}()")

        refuse.__name__ = name
        return refuse

    return {name: make(name) for name in names}


_LIST_MUTATORS = ("append", "extend", "insert", "pop", "remove", "sort", "reverse", "clear")
_DICT_MUTATORS = ("update", "pop", "popitem", "setdefault", "clear")
_SET_MUTATORS = ("add", "discard", "remove", "pop", "clear", "update")


class _View:
    """What every read-only view shares: the wrapped object, isinstance() seeing its type, its size, membership,
    equality and hash, and refusing attributes."""

    __slots__ = ("_ro_target",)

    def __init__(self, target: object) -> None:
        object.__setattr__(self, "_ro_target", target)

    @property  # type: ignore[misc]
    def __class__(self) -> type:  # makes isinstance(view, OriginalType) true
        return type(object.__getattribute__(self, "_ro_target"))

    def __repr__(self) -> str:
        return repr(object.__getattribute__(self, "_ro_target"))

    def __len__(self) -> int:
        return len(object.__getattribute__(self, "_ro_target"))

    def __contains__(self, item: object) -> bool:
        return item in object.__getattribute__(self, "_ro_target")

    def __setattr__(self, name: str, value: object) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), f"set attribute {name!r}")

    def __eq__(self, other: object) -> bool:
        return bool(object.__getattribute__(self, "_ro_target") == unwrap(other))

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)

    def __hash__(self) -> int:  # a view of an unhashable container sets it None, like its target
        return hash(object.__getattribute__(self, "_ro_target"))


class ReadOnlyObject(_View):
    """Read-only proxy of an arbitrary object (e.g. a ROS message): attributes come back read-only."""

    __slots__ = ()

    def __getattribute__(self, name: str) -> Any:  # every attribute read comes back read-only
        return readonly(getattr(object.__getattribute__(self, "_ro_target"), name))

    def __delattr__(self, name: str) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), f"delete attribute {name!r}")

    def __getitem__(self, key: Any) -> Any:
        return readonly(object.__getattribute__(self, "_ro_target")[key])

    def __setitem__(self, key: Any, value: object) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), "set an item")

    def __delitem__(self, key: Any) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), "delete an item")

    def __iter__(self) -> Iterator[Any]:
        return (readonly(v) for v in object.__getattribute__(self, "_ro_target"))

    def __bool__(self) -> bool:
        return bool(object.__getattribute__(self, "_ro_target"))

    def __str__(self) -> str:
        return str(object.__getattribute__(self, "_ro_target"))


class ReadOnlySequence(_View, Sequence[Any]):
    """Read-only view of a list or tuple; items come back read-only; mutators refuse. No copy."""

    __slots__ = ()

    def __getitem__(self, index: Any) -> Any:
        target = object.__getattribute__(self, "_ro_target")
        if isinstance(index, slice):
            return ReadOnlySequence(target[index])  # a slice copies; the copy is protected too
        return readonly(target[index])

    def __iter__(self) -> Iterator[Any]:
        return (readonly(v) for v in object.__getattribute__(self, "_ro_target"))

    def __setitem__(self, key: Any, value: object) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), "set an item")

    def __delitem__(self, key: Any) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), "delete an item")


class ReadOnlyMapping(_View, Mapping[Any, Any]):
    """Read-only view of a dict; values come back read-only; mutators refuse. No copy."""

    __slots__ = ()

    def __getitem__(self, key: Any) -> Any:
        return readonly(object.__getattribute__(self, "_ro_target")[key])

    def __iter__(self) -> Iterator[Any]:
        return iter(object.__getattribute__(self, "_ro_target"))

    def __setitem__(self, key: Any, value: object) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), "set an item")

    def __delitem__(self, key: Any) -> None:
        raise _refuse(object.__getattribute__(self, "_ro_target"), "delete an item")

    __hash__ = None  # type: ignore[assignment]  # unhashable, like dict


class ReadOnlySet(_View, AbstractSet[Any]):
    """Read-only view of a set (elements are hashable, returned as they are); mutators refuse. No copy."""

    __slots__ = ()

    def __iter__(self) -> Iterator[Any]:
        return iter(object.__getattribute__(self, "_ro_target"))

    __hash__ = None  # type: ignore[assignment]  # unhashable, like set


_VIEW_TYPES = frozenset({ReadOnlyObject, ReadOnlySequence, ReadOnlyMapping, ReadOnlySet})
_PASS_THROUGH = (enum.Enum, int, float, complex, str, bytes, *_CALLABLE_TYPES)
_SPECIAL_BASES_SET = frozenset({*_PASS_THROUGH, list, tuple, dict, set, frozenset, bytearray, memoryview})

for _view_class, _mutators in (
    (ReadOnlySequence, _LIST_MUTATORS),
    (ReadOnlyMapping, _DICT_MUTATORS),
    (ReadOnlySet, _SET_MUTATORS),
):
    for _name, _method in _refusing(*_mutators).items():
        setattr(_view_class, _name, _method)

# (container key, read through readonly()) per readable child key
ReadSpec = Dict[str, Tuple[str, bool]]


class UserDataView:
    """One child's window on its container's userdata store (built once per attach).

    ``read`` maps each declared input key to (store key, wrap read-only?); ``write`` maps each declared
    output key to its store key. ``owner`` is the state, for error messages.
    """

    __slots__ = ("_ud_owner", "_ud_read", "_ud_store", "_ud_write")

    def __init__(self, store: Dict[str, Any], read: ReadSpec, write: Dict[str, str], owner: State) -> None:
        object.__setattr__(self, "_ud_store", store)
        object.__setattr__(self, "_ud_read", read)
        object.__setattr__(self, "_ud_write", write)
        object.__setattr__(self, "_ud_owner", owner)

    def __getattr__(self, key: str) -> Any:
        if key.startswith(("__", "_ud_")):  # copy/pickle/inspect probes, slots of a half-built copy
            raise AttributeError(key)
        return self._ud_get(key)

    def __getitem__(self, key: str) -> Any:
        return self._ud_get(key)

    def _ud_get(self, key: str) -> Any:
        try:
            store_key, wrap = self._ud_read[key]
        except KeyError:
            raise UserDataKeyError(self._ud_undeclared(key, "reads", "input", self._ud_read)) from None
        try:
            value = self._ud_store[store_key]
        except KeyError:
            renamed = f" (remapped to {store_key!r})" if store_key != key else ""
            raise UserDataKeyError(
                f"state {self._ud_owner.path!r} reads userdata key {key!r}{renamed} which has no value yet "
                f"(keys with a value: {', '.join(sorted(self._ud_store)) or 'none'})"
            ) from None
        return readonly(value) if wrap else value

    def __setattr__(self, key: str, value: Any) -> None:
        self._ud_set(key, value)

    def __setitem__(self, key: str, value: Any) -> None:
        self._ud_set(key, value)

    def _ud_set(self, key: str, value: Any) -> None:
        try:
            store_key = self._ud_write[key]
        except KeyError:
            if key in self._ud_read:
                raise ReadOnlyUserDataError(
                    f"state {self._ud_owner.path!r} writes userdata key {key!r} which is input-only "
                    f"(outputs: {', '.join(self._ud_write) or 'none'})"
                ) from None
            raise UserDataKeyError(self._ud_undeclared(key, "writes", "output", self._ud_write)) from None
        self._ud_store[store_key] = value

    def __delattr__(self, key: str) -> None:
        raise ReadOnlyUserDataError(f"state {self._ud_owner.path!r} cannot delete userdata key {key!r}")

    def __copy__(self) -> UserDataView:
        """The same window (same store and declarations)."""
        return UserDataView(self._ud_store, self._ud_read, self._ud_write, self._ud_owner)

    def __deepcopy__(self, memo: Dict[int, Any]) -> UserDataView:
        raise TypeError("a userdata view cannot be deep-copied: copy the values you read from it")

    def __reduce__(self) -> Any:
        raise TypeError("a userdata view cannot be pickled: pickle the values you read from it")

    def __contains__(self, key: object) -> bool:
        """True if ``key`` is a declared input that has a value now."""
        spec = self._ud_read.get(key) if isinstance(key, str) else None
        return spec is not None and spec[0] in self._ud_store

    def get(self, key: str, default: Any = None) -> Any:
        """Value of declared input ``key``, or ``default`` if it has no value yet (undeclared still raises)."""
        if key not in self._ud_read:
            raise UserDataKeyError(self._ud_undeclared(key, "reads", "input", self._ud_read))
        return self._ud_get(key) if key in self else default

    def keys(self) -> Tuple[str, ...]:
        """The declared input and output keys (the child's names)."""
        return tuple(dict.fromkeys([*self._ud_read, *self._ud_write]))

    def _ud_undeclared(self, key: str, verb: str, kind: str, declared: Mapping[str, object]) -> str:
        return (
            f"state {self._ud_owner.path!r} {verb} userdata key {key!r} which it does not declare as {kind} "
            f"({kind}s: {', '.join(declared) or 'none'})"
        )

    def __repr__(self) -> str:
        return f"<UserDataView of {self._ud_owner.path!r}: {', '.join(self.keys())}>"


def view_parts(view: UserDataView) -> Tuple[Dict[str, Any], ReadSpec, Dict[str, str]]:
    """(store, read spec, write spec) of ``view``: for the containers, which copy a container's inputs
    in from its parent's store when it is entered and its outputs back when it finishes. (A function,
    not a method: a method name on the view would hide the userdata key of that name.)"""
    return view._ud_store, view._ud_read, view._ud_write
