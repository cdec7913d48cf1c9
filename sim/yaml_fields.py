"""Strict, typed reading of YAML mappings with errors that name the file, the field and what is valid.

Robot profiles and worlds are hand-written YAML. A typo must fail at load time with a message such as
``lab.yaml: obstacles[2].shape 'cube' is not valid (valid: box, cylinder)``, never be ignored. A
:class:`Fields` wraps one mapping plus its location (file and dotted path); every getter checks type
and range with :mod:`flex_nav.validation` (the file is the owner, the dotted path the parameter), and
:meth:`Fields.done` rejects keys nobody read (unknown fields, listing the known ones).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Set, Tuple, Union

import yaml

from flex_nav import validation
from flex_nav.exceptions import ConfigError, choices_message

PathLike = Union[str, Path]
_MISSING = object()


def read_yaml_mapping(path: Path, what: str) -> Dict[str, Any]:
    """Parse ``path`` as YAML and return its top-level mapping; ConfigError if unreadable or not a mapping."""
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ConfigError(f"{path}: cannot read {what} file: {err}") from err
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as err:
        raise ConfigError(f"{path}: malformed YAML in {what} file: {err}") from err
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: a {what} file must hold a YAML mapping at the top, got {type(data).__name__}")
    return data


def resolve_named_file(name_or_path: PathLike, folder: Path, what: str) -> Path:
    """``name`` -> ``folder/name.yaml``; an existing path is used as is. ConfigError lists the valid names."""
    text = str(name_or_path)
    if not text:
        raise ConfigError(choices_message(what, text, available_names(folder)))
    candidate = Path(text)
    if candidate.suffix in (".yaml", ".yml") or "/" in text:
        if candidate.is_file():
            return candidate
        raise ConfigError(
            f"{what} file {candidate} does not exist (or give one of: {', '.join(available_names(folder))})"
        )
    named = folder / f"{text}.yaml"
    if named.is_file():
        return named
    raise ConfigError(choices_message(what, text, available_names(folder)))


def available_names(folder: Path) -> List[str]:
    """The names (file stems) of the ``*.yaml`` files in ``folder``, sorted."""
    return sorted(p.stem for p in folder.glob("*.yaml"))


class Fields:
    """One YAML mapping being read: typed getters that raise ConfigError naming ``source: path.field``."""

    def __init__(self, data: object, source: str, path: str = "") -> None:
        if not isinstance(data, dict):
            where = f"{source}: {path}" if path else source
            raise ConfigError(f"{where} must be a mapping (key: value), got {validation.shown(data)}")
        self.data: Dict[str, Any] = data
        self.source = source
        self.path = path
        self._read: Set[str] = set()

    def where(self, key: str) -> str:
        """``source: path.key`` for messages."""
        return f"{self.source}: {self.dotted(key)}"

    def dotted(self, key: str) -> str:
        """``path.key``: where ``key`` is in the file."""
        return f"{self.path}.{key}" if self.path else key

    def has(self, key: str) -> bool:
        return key in self.data

    def raw(self, key: str, default: Any = _MISSING) -> Any:
        """The value as parsed, or ``default``; missing and no default -> ConfigError."""
        self._read.add(key)
        if key in self.data:
            return self.data[key]
        if default is _MISSING:
            raise ConfigError(f"{self.where(key)} is required but missing")
        return default

    def sub(self, key: str, default_empty: bool = False) -> Fields:
        """A nested mapping as :class:`Fields`."""
        value = self.raw(key, {} if default_empty else _MISSING)
        return Fields(value, self.source, self.dotted(key))

    def sub_list(self, key: str) -> List[Fields]:
        """A list of mappings (missing -> empty list)."""
        items = self.raw(key, [])
        if items is None:
            return []
        if not isinstance(items, list):
            raise ConfigError(f"{self.where(key)} must be a list, got {validation.shown(items)}")
        return [Fields(item, self.source, f"{self.dotted(key)}[{i}]") for i, item in enumerate(items)]

    def number(
        self,
        key: str,
        default: Optional[float] = None,
        *,
        minimum: Optional[float] = None,
        maximum: Optional[float] = None,
        positive: bool = False,
        unit: str = "",
    ) -> float:
        """A finite number within [minimum, maximum] (``positive``: > 0)."""
        value = self.raw(key, _MISSING if default is None else default)
        return validation.number(
            self.source, self.dotted(key), value, minimum=minimum, maximum=maximum, positive=positive, unit=unit
        )

    def positive(self, key: str, default: Optional[float] = None, unit: str = "") -> float:
        return self.number(key, default, positive=True, unit=unit)

    def integer(self, key: str, default: Optional[int] = None, *, minimum: Optional[int] = None) -> int:
        value = self.raw(key, _MISSING if default is None else default)
        return validation.integer(self.source, self.dotted(key), value, minimum=minimum)

    def boolean(self, key: str, default: Optional[bool] = None) -> bool:
        value = self.raw(key, _MISSING if default is None else default)
        return validation.boolean(self.source, self.dotted(key), value)

    def string(self, key: str, default: Optional[str] = None) -> str:
        value = self.raw(key, _MISSING if default is None else default)
        return validation.text(self.source, self.dotted(key), value)

    def choice(self, key: str, valid: Sequence[str], default: Optional[str] = None) -> str:
        value = self.raw(key, _MISSING if default is None else default)
        return validation.choice(self.source, self.dotted(key), value, valid)

    def vector(
        self, key: str, length: int, default: Optional[Sequence[float]] = None, unit: str = ""
    ) -> Tuple[float, ...]:
        """A list of exactly ``length`` finite numbers."""
        value = self.raw(key, _MISSING if default is None else list(default))
        return check_vector(value, self.source, self.dotted(key), (length,), unit)

    def pose(self, key: str, default: Optional[Sequence[float]] = None) -> Tuple[float, float, float]:
        """``[x, y]`` or ``[x, y, yaw_deg]`` -> (x [m], y [m], yaw [rad])."""
        value = self.raw(key, _MISSING if default is None else list(default))
        x, y, *rest = check_vector(
            value, self.source, self.dotted(key), (2, 3), "[x [m], y [m]] or [x [m], y [m], yaw [deg]]"
        )
        return x, y, math.radians(rest[0]) if rest else 0.0

    def points(self, key: str, minimum: int = 1) -> List[Tuple[float, float]]:
        """A list of ``[x, y]`` points [m], at least ``minimum`` of them."""
        value = self.raw(key)
        if not isinstance(value, list) or len(value) < minimum:
            raise ConfigError(
                f"{self.where(key)} must be a list of at least {minimum} [x, y] points [m], "
                f"got {validation.shown(value)}"
            )
        out = []
        for i, item in enumerate(value):
            x, y = check_vector(item, self.source, f"{self.dotted(key)}[{i}]", (2,), "[x [m], y [m]]")
            out.append((x, y))
        return out

    def done(self) -> None:
        """Reject keys that were never read (typos, unsupported options), naming the valid keys."""
        unknown = sorted(set(self.data) - self._read)
        if unknown:
            bad = unknown[0]
            raise ConfigError(choices_message(f"{self.where(str(bad))}: unknown field", bad, sorted(self._read)))


def check_vector(
    value: object, owner: str, name: str, lengths: Tuple[int, ...], unit: str = ""
) -> Tuple[float, ...]:
    """A list/tuple of finite numbers whose length is one of ``lengths``; messages name ``owner: name``."""
    wanted = " or ".join(str(n) for n in lengths)
    if not isinstance(value, (list, tuple)) or len(value) not in lengths:
        detail = f" {unit}" if unit else ""
        raise ConfigError(f"{owner}: {name} must be a list of {wanted} numbers{detail}, got {validation.shown(value)}")
    return tuple(validation.number(owner, f"{name}[{i}]", v) for i, v in enumerate(value))
