"""Behaviors defined in YAML, loaded with line numbers: every error reads ``file:line: what (valid: ...)``.

The schema is documented in ``docs/behavior_yaml.md``. In short::

    behavior: patrol                  # the name; the file is patrol.yaml
    description: Drive to two points, forever.
    parameters:                       # typed, overridable at load time
      pause_s: {type: float, default: 1.0, min: 0.0, description: "[s] pause at each point"}
    input_keys: [first, second]
    userdata: {count: 0}
    outcomes: [finished, failed]
    states:
      Pause:
        class: flex_nav.behavior.builtin_states.Wait
        parameters: {wait_time_s: $pause_s}
        transitions: {done: Drive}
        autonomy: {done: low}
      Drive:
        behavior: drive_to            # a sub-behavior, by name
        parameters: {speed: 0.2}
        transitions: {finished: Pause, failed: failed}
        remapping: {goal: first}

Containers nest with ``state_machine:``, ``concurrency:`` (with ``conditions``) and ``priority:``.
The file is read with ``yaml.compose`` so that every node keeps its line; names (labels, outcomes,
keys, autonomy levels) are taken as written, so ``off`` or ``yes`` stay strings there, while
parameter and userdata values are ordinary YAML values (``$name`` refers to a behavior parameter,
``$$`` escapes a literal ``$``). State classes are imported by their dotted path; nothing in a file is
evaluated. After building, the whole tree is validated and engine errors are mapped back to the
line that caused them.

Sub-behaviors are looked up by name as ``<name>.yaml``: first beside the including file, then in the
search path (``search_path`` argument, else the ``FLEX_NAV_BEHAVIOR_PATH`` directories, then the
package's ``behaviors/`` directory).

Where a behavior comes from is explicit (:class:`BehaviorSource`): a *remote* source (a name received over ROS,
:func:`load_named_behavior`) is only ever looked up in the search path; a *local* one (code, the runner's
``~behavior`` parameter) may also be a file path (a ``Path``, or a str with a ``/`` or a ``.yaml`` suffix). A
plain name is never taken from the working directory. Every load is bounded by
:class:`~flex_nav.behavior.yaml_limits.LoadLimits` (bytes, aliases, expanded nodes, nesting, states, include
depth, time) and every failure, whatever a file holds (not UTF-8, a state class raising anything), is a
FlexNavError.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import os
import re
from pathlib import Path
from typing import (
    Any,
    Callable,
    Dict,
    FrozenSet,
    List,
    Mapping,
    NoReturn,
    Optional,
    Sequence,
    Tuple,
    Type,
    TypeVar,
    Union,
)

import yaml
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from flex_nav.behavior.behavior import Behavior, ParameterInfo
from flex_nav.behavior.concurrency import ConcurrencyContainer
from flex_nav.behavior.container import Container, child_path
from flex_nav.behavior.priority import PriorityContainer
from flex_nav.behavior.state import State
from flex_nav.behavior.state_machine import StateMachine
from flex_nav.behavior.yaml_limits import DEFAULT_LIMITS, MAX_NAME_CHARS, LoadBudget, LoadLimits
from flex_nav.exceptions import (
    BehaviorConstructionError,
    BehaviorLoadError,
    ConfigError,
    FlexNavError,
    choices_message,
)
from flex_nav.resources import behaviors_dir

BEHAVIOR_PATH_ENV = "FLEX_NAV_BEHAVIOR_PATH"
PACKAGE_BEHAVIORS_DIR = behaviors_dir()
_NAME_RE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_\-]*$")
_STR_TAG = "tag:yaml.org,2002:str"

_TOP_KEYS = (
    "behavior",
    "description",
    "parameters",
    "input_keys",
    "output_keys",
    "userdata",
    "outcomes",
    "initial",
    "states",
)
_CONTAINER_KEYS = ("outcomes", "input_keys", "output_keys", "userdata", "initial", "states")
_CONCURRENCY_KEYS = ("outcomes", "input_keys", "output_keys", "userdata", "states", "conditions")
_KINDS = ("class", "state_machine", "concurrency", "priority", "behavior")
_PARAM_KEYS = ("type", "default", "min", "max", "choices", "description")
_PARAM_TYPES: Dict[str, Tuple[type, ...]] = {
    "float": (float, int),
    "int": (int,),
    "bool": (bool,),
    "str": (str,),
    "list": (list,),
    "dict": (dict,),
}

Where = Tuple[str, int]  # (file, 1-based line)
MarkKey = Tuple[str, Optional[str], Optional[str], Optional[str]]  # (container path, label, field, item)


def default_search_path() -> List[Path]:
    """Directories searched for behaviors by name: $FLEX_NAV_BEHAVIOR_PATH, then the package's behaviors/."""
    dirs = [Path(p) for p in os.environ.get(BEHAVIOR_PATH_ENV, "").split(os.pathsep) if p]
    if PACKAGE_BEHAVIORS_DIR.is_dir():
        dirs.append(PACKAGE_BEHAVIORS_DIR)
    return dirs


def list_behaviors(search_path: Optional[Sequence[Union[str, Path]]] = None) -> Dict[str, Path]:
    """Behavior names found in the search path (the first file of each name wins; unreadable directories and
    entries that are not regular files are skipped)."""
    found: Dict[str, Path] = {}
    for directory in _dirs(search_path):
        try:
            paths = sorted(directory.glob("*.yaml")) if directory.is_dir() else []
            for path in paths:
                if _NAME_RE.match(path.stem) and len(path.stem) <= MAX_NAME_CHARS and path.is_file():
                    found.setdefault(path.stem, path)
        except OSError:
            continue
    return found


def check_behavior_name(name: object) -> str:
    """``name`` if it is a plain behavior name (letters, digits, '_' or '-', at most MAX_NAME_CHARS); ConfigError
    saying why not. Looks at no file, so it is safe for names received remotely, however long."""
    if not isinstance(name, str):
        raise ConfigError(f"a behavior name must be a string, got {type(name).__name__}")
    if len(name) > MAX_NAME_CHARS:
        raise ConfigError(
            f"behavior name {name[:32]!r}... is {len(name)} characters long (at most {MAX_NAME_CHARS})"
        )
    if not _NAME_RE.match(name):
        raise ConfigError(f"behavior name {name!r} must be letters, digits, '_' or '-' (no paths)")
    return name


def find_behavior(name: str, search_path: Optional[Sequence[Union[str, Path]]] = None) -> Path:
    """The file ``<name>.yaml`` of behavior ``name`` in the search path (a plain name, checked by
    :func:`check_behavior_name`: safe for names received remotely). ConfigError listing the valid names."""
    check_behavior_name(name)
    dirs = _dirs(search_path)
    for directory in dirs:
        candidate = directory / f"{name}.yaml"
        try:
            if candidate.is_file():
                return candidate
        except OSError:  # e.g. a search path directory that cannot be read: the name is not there
            continue
    raise ConfigError(
        choices_message(
            f"behavior (looked in: {', '.join(str(d) for d in dirs) or 'no directories'})", name, list_behaviors(dirs)
        )
    )


@dataclasses.dataclass(frozen=True)
class BehaviorSource:
    """Where a behavior comes from, and how far it is trusted.

    - :meth:`remote`: a behavior *name*, looked up only in the search path. For names received from other
      nodes (the runner's ``start`` command): no file outside the search path is ever read or named.
    - :meth:`local`: a YAML file path (a ``Path``, or a str with a ``/`` or a ``.yaml``/``.yml`` suffix) or a
      name. For sources given by whoever starts the process (the runner's ``~behavior`` parameter, code).

    A plain str or Path given to :func:`load_behavior` is a local source.
    """

    text: str
    is_file: bool = False  # a file path (local only); else a name on the search path
    trusted: bool = True  # False: received remotely

    def __post_init__(self) -> None:
        if not self.trusted:  # however it was made, a remote source is a plain name
            check_behavior_name(self.text)
            if self.is_file:
                raise ConfigError(f"a behavior received remotely is a name on the search path, not a file: "
                                  f"{self.text!r}")

    @classmethod
    def remote(cls, name: str) -> BehaviorSource:
        """A name received remotely; ConfigError if it is not a plain behavior name."""
        return cls(check_behavior_name(name), is_file=False, trusted=False)

    @classmethod
    def local(cls, source: Union[str, Path]) -> BehaviorSource:
        if isinstance(source, Path):
            return cls(str(source), is_file=True)
        is_file = os.sep in source or "/" in source or source.endswith((".yaml", ".yml"))
        return cls(source, is_file=is_file)

    def resolve(self, search_path: Optional[Sequence[Union[str, Path]]] = None) -> Path:
        """The file to read: the path itself, or ``<name>.yaml`` found in the search path."""
        return Path(self.text) if self.is_file else find_behavior(self.text, search_path)


Source = Union[str, Path, BehaviorSource]


def _source(source: Source) -> BehaviorSource:
    return source if isinstance(source, BehaviorSource) else BehaviorSource.local(source)


def load_behavior(
    source: Source,
    parameters: Optional[Mapping[str, Any]] = None,
    search_path: Optional[Sequence[Union[str, Path]]] = None,
    limits: LoadLimits = DEFAULT_LIMITS,
) -> Behavior:
    """Load, build and validate a behavior: a :class:`BehaviorSource`, or (trusted, local) a file path or a name.

    ``parameters`` override the behavior's declared parameters (type-checked). The load is bounded by ``limits``
    (size, aliases, nodes, nesting, states, includes, time). Raises BehaviorLoadError (``file:line: ...``; its
    subclass BehaviorLoadLimitError names the limit crossed) for anything wrong in the files, and ConfigError for
    a bad name or parameter override: every failure is a FlexNavError, whatever the files hold.
    """
    resolved = _source(source)
    path = resolved.resolve(search_path)
    loader = _Loader(_dirs(search_path), LoadBudget(limits))
    return _guarded(lambda: loader.load_top(path, dict(parameters or {})), str(path))


def load_named_behavior(
    name: str,
    parameters: Optional[Mapping[str, Any]] = None,
    search_path: Optional[Sequence[Union[str, Path]]] = None,
    limits: LoadLimits = DEFAULT_LIMITS,
) -> Behavior:
    """:func:`load_behavior` of a name received remotely: only ``<name>.yaml`` in the search path."""
    return load_behavior(BehaviorSource.remote(name), parameters, search_path, limits)


def declared_parameter_names(
    source: Source, search_path: Optional[Sequence[Union[str, Path]]] = None, limits: LoadLimits = DEFAULT_LIMITS
) -> FrozenSet[str]:
    """The names under a behavior's ``parameters:`` (the file is read within ``limits``, nothing is built, so
    this is cheap and has no side effects). ConfigError for a bad name, BehaviorLoadError for a file that is not
    YAML."""
    path = _source(source).resolve(search_path)
    node = _guarded(lambda: _compose(LoadBudget(limits), path, None), str(path))
    if isinstance(node, MappingNode):
        for key_node, value_node in node.value:
            if isinstance(key_node, ScalarNode) and key_node.value == "parameters" and isinstance(
                value_node, MappingNode
            ):
                return frozenset(str(k.value) for k, _ in value_node.value if isinstance(k, ScalarNode))
    return frozenset()


def parameter_schema(
    source: Source, search_path: Optional[Sequence[Union[str, Path]]] = None, limits: LoadLimits = DEFAULT_LIMITS
) -> List[ParameterInfo]:
    """The declared parameters of a behavior (type, default, bounds, choices, description), checked as a load checks
    them, read within ``limits`` without building anything: for a form that starts it. ConfigError for a bad name,
    BehaviorLoadError (``file:line: ...``) for a bad file."""
    path = _source(source).resolve(search_path)
    loader = _Loader(_dirs(search_path), LoadBudget(limits))

    def read() -> List[ParameterInfo]:
        loader.file = str(path)
        top = loader.pairs(loader.compose(path, None), "a behavior file")
        if "parameters" not in top:
            return []
        specs = loader.pairs(top["parameters"][1], "parameters")
        return [loader.param_spec(name, key_node, spec_node).info() for name, (key_node, spec_node) in specs.items()]

    return _guarded(read, str(path))


def load_behavior_text(
    text: str,
    file: str = "<string>",
    parameters: Optional[Mapping[str, Any]] = None,
    search_path: Optional[Sequence[Union[str, Path]]] = None,
    limits: LoadLimits = DEFAULT_LIMITS,
) -> Behavior:
    """Like :func:`load_behavior` for YAML text (``file`` is only used in messages)."""
    loader = _Loader(_dirs(search_path), LoadBudget(limits))
    return _guarded(lambda: loader.load_top(Path(file), dict(parameters or {}), text=text), file)


_T = TypeVar("_T")
_C = TypeVar("_C", bound=Container)


def _guarded(load: Callable[[], _T], file: str) -> _T:
    """``load()``, with any failure that is not already a FlexNavError turned into a BehaviorLoadError."""
    try:
        return load()
    except FlexNavError:
        raise
    except (RecursionError, MemoryError) as err:
        raise BehaviorLoadError(f"the load ran out of resources ({type(err).__name__})", file, 0) from err
    except Exception as err:  # a state class can raise anything: the caller still gets a typed error
        raise BehaviorLoadError(f"the load failed: {type(err).__name__}: {err}", file, 0) from err


def _compose(budget: LoadBudget, path: Path, text: Optional[str]) -> Optional[Node]:
    """The YAML node tree of a file (or of ``text``) within ``budget``; BehaviorLoadError for bad YAML."""
    file = str(path)
    if text is None:
        text = budget.read_text(path)
    else:
        budget.count_text(text, file)
    try:
        return budget.compose(text, file)
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        line = mark.line + 1 if mark is not None else 0
        raise BehaviorLoadError(f"YAML syntax error: {err.problem or err}", file, line) from err
    except yaml.YAMLError as err:
        raise BehaviorLoadError(f"YAML error: {err}", file, 0) from err


def _dirs(search_path: Optional[Sequence[Union[str, Path]]]) -> List[Path]:
    return [Path(p) for p in search_path] if search_path is not None else default_search_path()


class _ParamSpec:
    def __init__(self, name: str, type_name: str, default: Any, has_default: bool, where: Where) -> None:
        self.name = name
        self.type_name = type_name
        self.default = default
        self.has_default = has_default
        self.minimum: Optional[float] = None
        self.maximum: Optional[float] = None
        self.choices: Optional[List[Any]] = None
        self.description = ""
        self.where = where

    def info(self) -> ParameterInfo:
        """What a tool shows of this parameter (the schema, without where it was written)."""
        choices = tuple(self.choices) if self.choices is not None else None
        return ParameterInfo(self.name, self.type_name, self.default, self.has_default, self.minimum, self.maximum,
                             choices, self.description)

    def check(self, value: Any) -> Any:
        """The value converted to the declared type, or ConfigError saying why not."""
        kinds = _PARAM_TYPES[self.type_name]
        if isinstance(value, bool) and self.type_name != "bool":
            raise ConfigError(f"parameter {self.name!r} must be {self.type_name}, got bool {value!r}")
        if not isinstance(value, kinds):
            raise ConfigError(f"parameter {self.name!r} must be {self.type_name}, got {type(value).__name__} {value!r}")
        if self.type_name == "float":
            value = float(value)  # type: ignore[arg-type]  # an int or float here
            if not math.isfinite(value):
                raise ConfigError(f"parameter {self.name!r} must be finite, got {value!r}")
        if self.minimum is not None and value < self.minimum:
            raise ConfigError(f"parameter {self.name!r} = {value!r} is below its minimum {self.minimum!r}")
        if self.maximum is not None and value > self.maximum:
            raise ConfigError(f"parameter {self.name!r} = {value!r} is above its maximum {self.maximum!r}")
        if self.choices is not None and value not in self.choices:
            raise ConfigError(choices_message(f"parameter {self.name!r} value", value, self.choices))
        return value


class _Loader:
    """One load: files on the include stack, marks from engine items to lines, YAML constructor."""

    def __init__(self, search_path: List[Path], budget: LoadBudget) -> None:
        self.search_path = search_path
        self.budget = budget
        self.marks: Dict[MarkKey, Where] = {}
        self.stack: List[Path] = []
        self.file = "<string>"
        self.params: Dict[str, Any] = {}
        self.schema: List[ParameterInfo] = []  # the top file's declared parameters
        self.sub_behaviors: Dict[str, str] = {}  # path of each included behavior -> its name
        self.constructor = yaml.SafeLoader("")

    # --- errors and marks ------------------------------------------------------------------------
    def fail(self, node: Optional[Node], message: str, where: Optional[Where] = None) -> NoReturn:
        if where is None:
            where = (self.file, node.start_mark.line + 1 if node is not None else 0)
        raise BehaviorLoadError(message, where[0], where[1])

    def mark(self, key: MarkKey, node: Node) -> None:
        self.marks[key] = (self.file, node.start_mark.line + 1)

    def engine_error(self, err: BehaviorConstructionError, fallback: Where) -> NoReturn:
        container = err.container or "/"
        item = None if err.item is None else str(err.item)
        keys: List[MarkKey] = [(container, None, err.field, item), (container, None, None, None)]
        if err.label is not None:
            keys[:0] = [(container, err.label, err.field, item), (container, err.label, None, None)]
        for key in keys:
            where = self.marks.get(key)
            if where is not None:
                break
        else:
            where = fallback
        raise BehaviorLoadError(str(err), where[0], where[1]) from err

    # --- node helpers --------------------------------------------------------------------------------
    def pairs(self, node: Node, what: str) -> Dict[str, Tuple[Node, Node]]:
        if not isinstance(node, MappingNode):
            self.fail(node, f"{what} must be a mapping, got {_kind(node)}")
        result: Dict[str, Tuple[Node, Node]] = {}
        for key_node, value_node in node.value:
            if not isinstance(key_node, ScalarNode) or not key_node.value:
                self.fail(key_node, f"keys of {what} must be plain names, got {_kind(key_node)}")
            key = key_node.value
            if key in result:
                self.fail(
                    key_node, f"duplicate key {key!r} in {what} (first on line {result[key][0].start_mark.line + 1})"
                )
            result[key] = (key_node, value_node)
        return result

    def only(self, pairs: Dict[str, Tuple[Node, Node]], valid: Sequence[str], what: str) -> None:
        for key, (key_node, _) in pairs.items():
            if key not in valid:
                self.fail(key_node, choices_message(f"unknown key in {what}:", key, valid))

    def name(self, node: Node, what: str) -> str:
        if not isinstance(node, ScalarNode) or node.value == "":
            self.fail(node, f"{what} must be a name, got {_kind(node)}")
        return str(node.value)

    def names(self, node: Node, what: str) -> List[Tuple[str, Node]]:
        if not isinstance(node, SequenceNode):
            self.fail(node, f"{what} must be a list of names, got {_kind(node)}")
        return [(self.name(item, f"each of {what}"), item) for item in node.value]

    def value(self, node: Node) -> Any:
        """The Python value of ``node``; ``$name`` scalars are behavior parameters."""
        if isinstance(node, ScalarNode):
            if node.tag == _STR_TAG and node.value.startswith("$"):
                if node.value.startswith("$$"):
                    return node.value[1:]
                name = node.value[1:]
                if name not in self.params:
                    self.fail(node, choices_message("parameter reference", node.value, [f"${p}" for p in self.params]))
                return self.params[name]
            return self.constructor.construct_object(node, deep=True)
        if isinstance(node, SequenceNode):
            return [self.value(item) for item in node.value]
        if isinstance(node, MappingNode):
            return {self.value(k): self.value(v) for k, v in node.value}
        self.fail(node, f"unexpected YAML node {_kind(node)}")

    # --- files --------------------------------------------------------------------------------------------
    def compose(self, path: Path, text: Optional[str]) -> Node:
        node = _compose(self.budget, path, text)
        if node is None:
            what = "the file is empty (a behavior needs behavior:, outcomes: and states:)"
            raise BehaviorLoadError(what, str(path), 1)
        return node

    def load_top(self, path: Path, overrides: Dict[str, Any], text: Optional[str] = None) -> Behavior:
        root, name, description, params = self.load_file(path, overrides, "/", None, text)
        try:
            root.validate()
        except BehaviorConstructionError as err:
            self.engine_error(err, (str(path), 1))
        return Behavior(name, root, description, params, path if text is None else None, parameter_schema=self.schema,
                        sub_behaviors=self.sub_behaviors)

    def load_file(
        self,
        path: Path,
        overrides: Dict[str, Any],
        cpath: str,
        included_at: Optional[Where],
        text: Optional[str] = None,
    ) -> Tuple[StateMachine, str, str, Dict[str, Any]]:
        outer_file, outer_params = self.file, self.params
        resolved = path.resolve() if text is None else path
        if resolved in self.stack:
            chain = " -> ".join(p.stem for p in [*self.stack, resolved])
            raise BehaviorLoadError(f"behavior includes itself: {chain}", *(included_at or (str(path), 0)))
        if len(self.stack) > self.budget.limits.max_include_depth:
            chain = " -> ".join(p.stem for p in [*self.stack, resolved])
            what = f"sub-behaviors nested more than {self.budget.limits.max_include_depth} deep: {chain}"
            raise self.budget.exceeded("max_include_depth", what, *(included_at or (str(path), 0)))
        self.stack.append(resolved)
        self.file = str(path)
        try:
            node = self.compose(path, text)
            top = self.pairs(node, "a behavior file")
            self.only(top, _TOP_KEYS, "a behavior file")
            for required in ("behavior", "outcomes", "states"):
                if required not in top:
                    self.fail(node, f"a behavior file needs the key {required!r} (keys: {', '.join(_TOP_KEYS)})")
            name_node = top["behavior"][1]
            name = self.name(name_node, "behavior")
            if not _NAME_RE.match(name):
                self.fail(name_node, f"behavior name {name!r} must be letters, digits, '_' or '-'")
            if text is None and path.stem != name:
                self.fail(name_node, f"behavior {name!r} must be in a file named {name}.yaml, not {path.name}")
            description = ""
            if "description" in top:
                description = str(self.value(top["description"][1]))
            self.params = self.parameters(top.get("parameters"), overrides, name, included_at)
            root = self.machine(top, StateMachine, cpath, node)
            return root, name, description, dict(self.params)
        finally:
            self.stack.pop()
            self.file, self.params = outer_file, outer_params

    def parameters(
        self, entry: Optional[Tuple[Node, Node]], overrides: Dict[str, Any], behavior: str, included_at: Optional[Where]
    ) -> Dict[str, Any]:
        specs: Dict[str, _ParamSpec] = {}
        if entry is not None:
            for pname, (key_node, spec_node) in self.pairs(entry[1], "parameters").items():
                specs[pname] = self.param_spec(pname, key_node, spec_node)
        if included_at is None:
            self.schema = [spec.info() for spec in specs.values()]
        values: Dict[str, Any] = {}
        for pname, value in overrides.items():
            if pname not in specs:
                message = choices_message(f"behavior {behavior!r} has no parameter; override", pname, specs)
                if included_at is not None:
                    raise BehaviorLoadError(message, *included_at)
                raise ConfigError(message)
            try:
                values[pname] = specs[pname].check(value)
            except ConfigError as err:
                message = f"behavior {behavior!r}: override of {err}"
                if included_at is not None:
                    raise BehaviorLoadError(message, *included_at) from err
                raise ConfigError(message) from err
        for pname, spec in specs.items():
            if pname not in values:
                if not spec.has_default:
                    message = f"behavior {behavior!r} needs a value for parameter {pname!r} (it has no default)"
                    raise BehaviorLoadError(message, *(included_at or spec.where))
                values[pname] = spec.default
        return values

    def param_spec(self, pname: str, key_node: Node, spec_node: Node) -> _ParamSpec:
        spec_pairs = self.pairs(spec_node, f"parameter {pname!r}")
        self.only(spec_pairs, _PARAM_KEYS, f"parameter {pname!r}")
        if "type" not in spec_pairs:
            self.fail(spec_node, f"parameter {pname!r} needs a type (valid: {', '.join(_PARAM_TYPES)})")
        type_node = spec_pairs["type"][1]
        type_name = self.name(type_node, f"type of parameter {pname!r}")
        if type_name not in _PARAM_TYPES:
            self.fail(type_node, choices_message(f"type of parameter {pname!r}", type_name, _PARAM_TYPES))
        has_default = "default" in spec_pairs
        spec = _ParamSpec(pname, type_name, None, has_default, (self.file, key_node.start_mark.line + 1))
        for bound in ("min", "max"):
            if bound in spec_pairs:
                bound_node = spec_pairs[bound][1]
                value = self.constructor.construct_object(bound_node, deep=True)
                numeric = isinstance(value, (int, float)) and not isinstance(value, bool)
                if type_name not in ("float", "int") or not numeric:
                    self.fail(bound_node, f"{bound} of parameter {pname!r} needs a number and a float or int type")
                setattr(spec, "minimum" if bound == "min" else "maximum", value)
        if "choices" in spec_pairs:
            choices = self.constructor.construct_object(spec_pairs["choices"][1], deep=True)
            if not isinstance(choices, list) or not choices:
                self.fail(spec_pairs["choices"][1], f"choices of parameter {pname!r} must be a non-empty list")
            spec.choices = choices
        if "description" in spec_pairs:
            spec.description = str(self.constructor.construct_object(spec_pairs["description"][1], deep=True))
        if has_default:
            default_node = spec_pairs["default"][1]
            try:
                spec.default = spec.check(self.constructor.construct_object(default_node, deep=True))
            except ConfigError as err:
                self.fail(default_node, f"default of {err}")
        return spec

    # --- containers ------------------------------------------------------------------------------------------
    def container_head(self, pairs: Dict[str, Tuple[Node, Node]], what: str, node: Node) -> Dict[str, Any]:
        if "outcomes" not in pairs:
            self.fail(node, f"{what} needs outcomes")
        if "states" not in pairs:
            self.fail(node, f"{what} needs states")
        head: Dict[str, Any] = {"outcomes": [n for n, _ in self.names(pairs["outcomes"][1], "outcomes")]}
        for key in ("input_keys", "output_keys"):
            head[key] = [n for n, _ in self.names(pairs[key][1], key)] if key in pairs else []
        if "userdata" in pairs:
            defaults = self.pairs(pairs["userdata"][1], "userdata")
            head["userdata"] = {key: self.value(value_node) for key, (_, value_node) in defaults.items()}
        return head

    def new_container(
        self, cls: Type[_C], pairs: Dict[str, Tuple[Node, Node]], what: str, cpath: str, node: Node
    ) -> _C:
        """The container of the head in ``pairs`` (outcomes, keys, userdata defaults), its head marked and its
        path set for add-time messages; the error of a bad head names the file and line."""
        head = self.container_head(pairs, what, node)
        self.mark((cpath, None, None, None), pairs["states"][0])
        try:
            container = cls(**head)
        except ConfigError as err:
            self.fail(node, f"{what}: {err}")
        container.__flex_nav_runtime__.path = cpath  # for add-time messages; attach sets it again
        if "output_keys" in pairs:
            for key_name, key_node in self.names(pairs["output_keys"][1], "output_keys"):
                self.mark((cpath, None, "key", key_name), key_node)
        return container

    def machine(
        self, pairs: Dict[str, Tuple[Node, Node]], cls: Type[StateMachine], cpath: str, node: Node
    ) -> StateMachine:
        what = f"{cls.kind} {cpath}"
        sm = self.new_container(cls, pairs, what, cpath, node)
        if "initial" in pairs:
            initial_node = pairs["initial"][1]
            sm.set_initial_state(self.name(initial_node, "initial"))
            self.mark((cpath, None, "initial", None), initial_node)
            self.mark((cpath, None, "initial", initial_node.value), initial_node)
        states = self.pairs(pairs["states"][1], f"states of {what}")
        for label, (label_node, state_node) in states.items():
            self.budget.count_state(self.file, label_node.start_mark.line + 1)
            path = child_path(cpath, label)
            self.mark((cpath, label, None, None), label_node)
            self.mark((cpath, label, "label", label), label_node)
            entry = self.pairs(state_node, f"state {label!r}")
            state = self.state(entry, label, path, label_node, in_concurrency=False)
            transitions = self.links(entry, "transitions", cpath, label)
            autonomy = self.links(entry, "autonomy", cpath, label)
            remapping = self.links(entry, "remapping", cpath, label)
            try:
                sm.add(label, state, transitions=transitions, autonomy=autonomy, remapping=remapping)
            except BehaviorConstructionError as err:
                err.container = cpath
                self.engine_error(err, (self.file, label_node.start_mark.line + 1))
        return sm

    def links(self, entry: Dict[str, Tuple[Node, Node]], key: str, cpath: str, label: str) -> Dict[str, str]:
        """transitions / autonomy / remapping of a state: names as written, each item marked."""
        if key not in entry:
            return {}
        field = {"transitions": "transition", "autonomy": "autonomy", "remapping": "remapping"}[key]
        result: Dict[str, str] = {}
        for item, (item_node, value_node) in self.pairs(entry[key][1], f"{key} of {label!r}").items():
            result[item] = self.name(value_node, f"{key} of {label!r}.{item}")
            self.mark((cpath, label, field, item), item_node)
        return result

    def concurrency(self, pairs: Dict[str, Tuple[Node, Node]], cpath: str, node: Node) -> ConcurrencyContainer:
        what = f"concurrency container {cpath}"
        self.only(pairs, _CONCURRENCY_KEYS, what)
        cc = self.new_container(ConcurrencyContainer, pairs, what, cpath, node)
        for label, (label_node, state_node) in self.pairs(pairs["states"][1], f"states of {what}").items():
            self.budget.count_state(self.file, label_node.start_mark.line + 1)
            self.mark((cpath, label, None, None), label_node)
            self.mark((cpath, label, "label", label), label_node)
            entry = self.pairs(state_node, f"state {label!r}")
            state = self.state(entry, label, child_path(cpath, label), label_node, in_concurrency=True)
            autonomy = self.links(entry, "autonomy", cpath, label)
            remapping = self.links(entry, "remapping", cpath, label)
            try:
                cc.add(label, state, remapping=remapping, autonomy=autonomy)
            except BehaviorConstructionError as err:
                err.container = cpath
                self.engine_error(err, (self.file, label_node.start_mark.line + 1))
        if "conditions" not in pairs:
            self.fail(node, f"{what} needs conditions (a list of {{outcome: ..., when: [[state, outcome], ...]}})")
        conditions_node = pairs["conditions"][1]
        if not isinstance(conditions_node, SequenceNode):
            self.fail(conditions_node, f"conditions of {what} must be a list, got {_kind(conditions_node)}")
        for condition_node in conditions_node.value:
            condition = self.pairs(condition_node, f"a condition of {what}")
            self.only(condition, ("outcome", "when"), f"a condition of {what}")
            if "outcome" not in condition or "when" not in condition:
                self.fail(condition_node, "a condition needs outcome: and when: [[state, outcome], ...]")
            outcome = self.name(condition["outcome"][1], "condition outcome")
            self.mark((cpath, None, "condition", outcome), condition_node)
            when_node = condition["when"][1]
            if not isinstance(when_node, SequenceNode):
                self.fail(when_node, f"when of condition {outcome!r} must be a list of [state, outcome] pairs")
            when: List[Tuple[str, str]] = []
            for pair_node in when_node.value:
                if not isinstance(pair_node, SequenceNode) or len(pair_node.value) != 2:
                    self.fail(pair_node, f"each item of when of condition {outcome!r} must be a pair [state, outcome]")
                child = self.name(pair_node.value[0], "state of a condition")
                child_outcome = self.name(pair_node.value[1], "outcome of a condition")
                self.mark((cpath, child, "condition", outcome), pair_node)
                when.append((child, child_outcome))
            cc.add_condition(outcome, when)
        return cc

    # --- states --------------------------------------------------------------------------------------------------
    def state(
        self, entry: Dict[str, Tuple[Node, Node]], label: str, path: str, node: Node, in_concurrency: bool
    ) -> State:
        kinds = [k for k in _KINDS if k in entry]
        if len(kinds) != 1:
            found = ", ".join(kinds) or "none"
            self.fail(node, f"state {label!r} needs exactly one of {', '.join(_KINDS)} (found: {found})")
        kind = kinds[0]
        links = ("autonomy", "remapping") if in_concurrency else ("transitions", "autonomy", "remapping")
        if kind == "class":
            self.only(entry, ("class", "parameters", "rate_hz", *links), f"state {label!r}")
            state = self.leaf(entry, label, node)
            if "rate_hz" in entry:
                rate_node = entry["rate_hz"][1]
                try:
                    state.rate_hz = self.value(rate_node)
                except ConfigError as err:
                    self.fail(rate_node, f"state {label!r}: {err}")
            return state
        if kind == "behavior":
            self.only(entry, ("behavior", "parameters", *links), f"state {label!r}")
            return self.sub_behavior(entry, label, path)
        self.only(entry, (kind, *links), f"state {label!r}")
        kind_node, body_node = entry[kind]
        body = self.pairs(body_node, f"{kind} of {label!r}")
        if kind == "concurrency":
            return self.concurrency(body, path, kind_node)
        cls: Type[StateMachine] = PriorityContainer if kind == "priority" else StateMachine
        self.only(body, _CONTAINER_KEYS, f"{kind} of {label!r}")
        return self.machine(body, cls, path, kind_node)

    def leaf(self, entry: Dict[str, Tuple[Node, Node]], label: str, node: Node) -> State:
        class_node = entry["class"][1]
        class_path = self.name(class_node, f"class of {label!r}")
        cls = self.import_state_class(class_path, class_node)
        params: Dict[str, Any] = {}
        param_nodes: Dict[str, Node] = {}
        if "parameters" in entry:
            for pname, (pkey, pvalue) in self.pairs(entry["parameters"][1], f"parameters of {label!r}").items():
                params[pname] = self.value(pvalue)
                param_nodes[pname] = pkey
        signature = inspect.signature(cls.__init__)
        accepted = [
            n
            for n, p in signature.parameters.items()
            if n != "self" and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
        ]
        takes_any = any(p.kind is p.VAR_KEYWORD for p in signature.parameters.values())
        for pname, pnode in param_nodes.items():
            if pname not in accepted and not takes_any:
                self.fail(pnode, choices_message(f"state class {cls.__name__} has no parameter", pname, accepted))
        missing = [
            n
            for n, p in signature.parameters.items()
            if n in accepted and p.default is p.empty and p.kind is not p.VAR_POSITIONAL and n not in params
        ]
        if missing:
            self.fail(
                entry["parameters"][0] if "parameters" in entry else class_node,
                f"state {label!r}: {cls.__name__} needs parameter(s) {', '.join(missing)} "
                f"(parameters: {', '.join(accepted)})",
            )
        try:
            return cls(**params)
        except (ConfigError, ValueError, TypeError) as err:
            self.fail(class_node, f"state {label!r}: {cls.__name__} rejected its parameters: {err}")

    def import_state_class(self, class_path: str, node: Node) -> Type[State]:
        module_name, _, class_name = class_path.rpartition(".")
        if not module_name:
            self.fail(node, f"class {class_path!r} must be a dotted path module.Class")
        try:
            module = importlib.import_module(module_name)
        except ImportError as err:
            self.fail(node, f"cannot import module {module_name!r} for state class {class_path!r}: {err}")
        states = sorted(
            n
            for n, obj in vars(module).items()
            if inspect.isclass(obj) and issubclass(obj, State) and not issubclass(obj, Container)
        )
        cls = getattr(module, class_name, None)
        if cls is None:
            self.fail(node, choices_message(f"module {module_name!r} has no state class", class_name, states))
        if not inspect.isclass(cls) or not issubclass(cls, State):
            self.fail(node, f"{class_path!r} is not a State class (state classes there: {', '.join(states) or 'none'})")
        if issubclass(cls, Container):
            self.fail(node, f"{class_path!r} is a container: use state_machine:, concurrency: or priority: instead")
        return cls

    def sub_behavior(self, entry: Dict[str, Tuple[Node, Node]], label: str, path: str) -> StateMachine:
        name_node = entry["behavior"][1]
        name = self.name(name_node, f"behavior of {label!r}")
        if name.startswith("$") and not name.startswith("$$"):  # a str parameter names the sub-behavior
            chosen = self.value(name_node)
            if not isinstance(chosen, str) or not chosen:
                self.fail(name_node, f"behavior of {label!r}: parameter {name} must name a behavior, got {chosen!r}")
            name = chosen
        where = (self.file, name_node.start_mark.line + 1)
        dirs = [Path(self.file).parent, *self.search_path] if self.file != "<string>" else list(self.search_path)
        try:
            file = find_behavior(name, dirs)
        except ConfigError as err:
            raise BehaviorLoadError(f"state {label!r}: {err}", *where) from err
        overrides: Dict[str, Any] = {}
        if "parameters" in entry:
            for pname, (_, pvalue) in self.pairs(entry["parameters"][1], f"parameters of {label!r}").items():
                overrides[pname] = self.value(pvalue)
        root, _, _, _ = self.load_file(file, overrides, path, where)
        self.sub_behaviors[path] = name
        return root


def _kind(node: Optional[Node]) -> str:
    if isinstance(node, MappingNode):
        return "a mapping"
    if isinstance(node, SequenceNode):
        return "a list"
    if isinstance(node, ScalarNode):
        return f"the value {node.value!r}" if node.value else "an empty value"
    return "nothing"


__all__ = [
    "BEHAVIOR_PATH_ENV",
    "DEFAULT_LIMITS",
    "BehaviorSource",
    "LoadLimits",
    "check_behavior_name",
    "declared_parameter_names",
    "default_search_path",
    "find_behavior",
    "list_behaviors",
    "load_behavior",
    "load_behavior_text",
    "load_named_behavior",
    "parameter_schema",
]
