"""Bounds on one YAML load, so that no file (or command argument) can make a load hang or exhaust memory.

A load reads behavior files (the top file and every sub-behavior it includes, each time it is included)
through one :class:`LoadBudget`; each limit of :class:`LoadLimits` is counted over the whole load and a
load that crosses one stops with :class:`~flex_nav.exceptions.BehaviorLoadLimitError` naming the limit
and its value. The defaults (``DEFAULT_LIMITS``) leave a wide margin over the largest shipped behavior
(``behaviors/``: move_base_like reads 6 files, 17 876 bytes; push_or_avoid builds 43 states; the deepest
YAML nesting is 10 levels and the deepest include chain 3 files; no shipped file uses aliases):

=====================  ==============  ================================================================
limit                  default         what is counted
=====================  ==============  ================================================================
``max_bytes``          1 MiB           bytes read in one load (top file and every included file)
``max_yaml_nodes``     50 000          YAML nodes with aliases expanded (a ``*ref`` counts its whole tree)
``max_aliases``        1 000           alias references (``*ref``)
``max_yaml_depth``     64              nesting of mappings and lists, aliases expanded
``max_states``         1 000           states built (containers and sub-behaviors' states included)
``max_include_depth``  16              sub-behaviors within sub-behaviors
``max_load_s``         10 s            wall time of the load (checked between files and states)
=====================  ==============  ================================================================

Expanded sizes are computed once per distinct node (aliases share nodes), so an "alias bomb" (a few
hundred bytes that expand to billions of nodes) is refused in milliseconds, before anything walks it.
Files must be UTF-8 regular files. Nothing here is global: each load makes its own budget.
"""

from __future__ import annotations

import dataclasses
import os
import stat
import time
from pathlib import Path
from typing import Any, Dict, List, Optional, Set, Tuple

import yaml
from yaml.events import AliasEvent
from yaml.nodes import MappingNode, Node, SequenceNode

from flex_nav.exceptions import BehaviorLoadError, BehaviorLoadLimitError, ConfigError

MAX_NAME_CHARS = 128  # a behavior name (the file is NAME.yaml; NAME_MAX is 255 bytes)


@dataclasses.dataclass(frozen=True)
class LoadLimits:
    """Bounds on one load (see the module docstring for what each counts and why the defaults)."""

    max_bytes: int = 1024 * 1024  # [bytes]
    max_yaml_nodes: int = 50_000
    max_aliases: int = 1_000
    max_yaml_depth: int = 64  # [levels]
    max_states: int = 1_000
    max_include_depth: int = 16  # [files] nested sub-behaviors below the top file
    max_load_s: float = 10.0  # [s] wall time

    def __post_init__(self) -> None:
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
                raise ConfigError(f"load limit {field.name} must be a positive number, got {value!r}")


DEFAULT_LIMITS = LoadLimits()


def _line(node: Optional[Node]) -> int:
    return node.start_mark.line + 1 if node is not None else 0


class LoadBudget:
    """What one load has used so far; every read, compose and state goes through it."""

    def __init__(self, limits: LoadLimits = DEFAULT_LIMITS) -> None:
        self.limits = limits
        self.bytes = 0
        self.nodes = 0
        self.aliases = 0
        self.states = 0
        self.deadline = time.monotonic() + limits.max_load_s

    def exceeded(self, limit: str, what: str, file: str, line: int) -> BehaviorLoadLimitError:
        value = getattr(self.limits, limit)
        return BehaviorLoadLimitError(f"{what} (limit {limit}={value})", limit, value, file, line)

    def check_time(self, file: str, line: int) -> None:
        if time.monotonic() > self.deadline:
            raise self.exceeded("max_load_s", f"loading took longer than {self.limits.max_load_s:g} s", file, line)

    def count_state(self, file: str, line: int) -> None:
        self.states += 1
        if self.states > self.limits.max_states:
            raise self.exceeded("max_states", f"more than {self.limits.max_states} states", file, line)
        self.check_time(file, line)

    def read_text(self, path: Path) -> str:
        """The file's text: a regular file, UTF-8, within what is left of ``max_bytes``."""
        file = str(path)
        self.check_time(file, 0)
        left = self.limits.max_bytes - self.bytes
        try:
            if not stat.S_ISREG(os.stat(path).st_mode):
                raise BehaviorLoadError("cannot read the file: not a regular file", file, 0)
            with open(path, "rb") as stream:
                data = stream.read(left + 1)
        except OSError as err:
            raise BehaviorLoadError(f"cannot read the file: {err.strerror or type(err).__name__}", file, 0) from err
        self.bytes += len(data)
        if len(data) > left:
            what = f"the behavior files of this load are larger than {self.limits.max_bytes} bytes"
            raise self.exceeded("max_bytes", what, file, 0)
        return decode_utf8(data, file)

    def count_text(self, text: str, file: str) -> None:
        """Count ``text`` (given, not read from a file) against ``max_bytes``."""
        self.bytes += len(text.encode("utf-8", "surrogatepass"))
        if self.bytes > self.limits.max_bytes:
            raise self.exceeded("max_bytes", f"the YAML text is larger than {self.limits.max_bytes} bytes", file, 0)

    def compose(self, text: str, file: str) -> Optional[Node]:
        """The YAML node tree of ``text`` (None if empty), with nesting, aliases and expanded size counted."""
        self.check_time(file, 0)
        composer = _BoundedComposer(text, self, file)
        try:
            node: Optional[Node] = composer.get_single_node()
        finally:
            composer.dispose()
        if node is not None:
            self.nodes += _Expansion(self, file).size(node)
            if self.nodes > self.limits.max_yaml_nodes:
                what = f"the YAML of this load expands to more than {self.limits.max_yaml_nodes} nodes"
                raise self.exceeded("max_yaml_nodes", what, file, _line(node))
        return node


def decode_utf8(data: bytes, file: str) -> str:
    """``data`` as UTF-8 text; BehaviorLoadError naming the byte offset (not the bytes) when it is not."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data.count(b"\n", 0, err.start) + 1
        raise BehaviorLoadError(f"the file is not UTF-8 text (invalid byte at offset {err.start})", file, line) from err


class _BoundedComposer(yaml.SafeLoader):
    """PyYAML's safe composer, counting alias references and nesting as it goes."""

    def __init__(self, text: str, budget: LoadBudget, file: str) -> None:
        super().__init__(text)
        self.budget = budget
        self.file = file
        self.depth = 0
        self.composed = 0  # nodes composed from the text (aliases not expanded)

    def compose_node(self, parent: Optional[Node], index: Any) -> Optional[Node]:
        event = self.peek_event()
        line = event.start_mark.line + 1 if event.start_mark is not None else 0
        limits = self.budget.limits
        if isinstance(event, AliasEvent):
            self.budget.aliases += 1
            if self.budget.aliases > limits.max_aliases:
                what = f"more than {limits.max_aliases} alias references (*name)"
                raise self.budget.exceeded("max_aliases", what, self.file, line)
        else:  # a node of the text: stop composing as soon as the load has too many, before expanding aliases
            self.composed += 1
            if self.budget.nodes + self.composed > limits.max_yaml_nodes:
                what = f"the YAML of this load has more than {limits.max_yaml_nodes} nodes"
                raise self.budget.exceeded("max_yaml_nodes", what, self.file, line)
        if self.depth >= limits.max_yaml_depth:
            what = f"YAML nested deeper than {limits.max_yaml_depth} levels"
            raise self.budget.exceeded("max_yaml_depth", what, self.file, line)
        self.depth += 1
        try:
            return super().compose_node(parent, index)
        finally:
            self.depth -= 1


class _Expansion:
    """Size and height of a node graph with aliases expanded, each distinct node walked once."""

    def __init__(self, budget: LoadBudget, file: str) -> None:
        self.budget = budget
        self.file = file
        self.known: Dict[int, Tuple[int, int]] = {}  # id(node) -> (expanded size, height)
        self.open: Set[int] = set()

    def size(self, root: Node) -> int:
        return self.walk(root, 1)[0]

    def walk(self, node: Node, depth: int) -> Tuple[int, int]:
        limits = self.budget.limits
        known = self.known.get(id(node))
        if known is None:
            if id(node) in self.open:
                raise BehaviorLoadError("an alias refers to a node that contains it (recursive data)",
                                        self.file, _line(node))
            children: List[Node] = []
            if isinstance(node, SequenceNode):
                children = list(node.value)
            elif isinstance(node, MappingNode):
                children = [item for pair in node.value for item in pair]
            if children and depth >= limits.max_yaml_depth:
                what = f"YAML nested deeper than {limits.max_yaml_depth} levels (aliases expanded)"
                raise self.budget.exceeded("max_yaml_depth", what, self.file, _line(node))
            self.open.add(id(node))
            size, height = 1, 1
            for child in children:
                child_size, child_height = self.walk(child, depth + 1)
                size += child_size
                height = max(height, child_height + 1)
                if self.budget.nodes + size > limits.max_yaml_nodes:
                    what = f"the YAML of this load expands to more than {limits.max_yaml_nodes} nodes"
                    raise self.budget.exceeded("max_yaml_nodes", what, self.file, _line(child))
            self.open.discard(id(node))
            known = self.known[id(node)] = (size, height)
        if depth + known[1] - 1 > limits.max_yaml_depth:
            what = f"YAML nested deeper than {limits.max_yaml_depth} levels (aliases expanded)"
            raise self.budget.exceeded("max_yaml_depth", what, self.file, _line(node))
        return known


def safe_load_bounded(text: str, what: str, limits: LoadLimits = DEFAULT_LIMITS) -> Any:
    """``yaml.safe_load(text)`` within ``limits`` (size, aliases, expanded nodes, nesting); ``what`` names the
    text in errors (BehaviorLoadError, BehaviorLoadLimitError). For values received over ROS."""
    budget = LoadBudget(limits)
    budget.count_text(text, what)
    try:
        node = budget.compose(text, what)
    except yaml.YAMLError as err:
        raise BehaviorLoadError(f"not valid YAML: {err}", what, 0) from err
    if node is None:
        return None
    constructor = yaml.SafeLoader("")
    try:
        return constructor.construct_document(node)
    except yaml.YAMLError as err:
        raise BehaviorLoadError(f"not valid YAML: {err}", what, 0) from err
    finally:
        constructor.dispose()


__all__ = ["DEFAULT_LIMITS", "MAX_NAME_CHARS", "LoadBudget", "LoadLimits", "decode_utf8", "safe_load_bounded"]
