"""Issue 22, parts 1 and 2: what a behavior load reads and how much it may cost.

Names received remotely are looked up only on the search path (never the working directory) and a refusal
never repeats what a file outside it holds; every load is bounded (bytes, aliases, expanded nodes, nesting,
states, includes, time) and every failure is a typed FlexNavError.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import textwrap
import time
import types
from pathlib import Path

import pytest
from harness import run_command_bounded

from flex_nav.behavior.state import State
from flex_nav.behavior.yaml_limits import DEFAULT_LIMITS, MAX_NAME_CHARS, LoadLimits, safe_load_bounded
from flex_nav.behavior.yaml_loader import (
    BehaviorSource,
    declared_parameter_names,
    find_behavior,
    list_behaviors,
    load_behavior,
    load_behavior_text,
    load_named_behavior,
)
from flex_nav.exceptions import BehaviorLoadError, BehaviorLoadLimitError, ConfigError, FlexNavError

REPO = Path(__file__).resolve().parents[3]
BEHAVIORS = REPO / "behaviors"
LOG = "flex_nav.behavior.builtin_states.Log"
SECRET = "s3cret-token-0xC0FFEE"
BOMB_LOAD_BOUND_S = 1.0  # [s] the alias bomb must be refused within this (measured: a few ms)
BOMB_PROCESS_BOUND_S = 60.0  # [s] the whole subprocess (imports included); the old code never returned


def chain(n: int, name: str = "big") -> str:
    """A behavior of ``n`` Log states in a row."""
    lines = [f"behavior: {name}", "outcomes: [done]", "states:"]
    for i in range(n):
        after = f"S{i + 1}" if i + 1 < n else "done"
        lines += [f"  S{i}:", f"    class: {LOG}", "    parameters: {text: x}", f"    transitions: {{done: {after}}}"]
    return "\n".join(lines) + "\n"


def laughs(levels: int = 9, indent: str = "") -> list:
    """ "Billion laughs": ``levels`` anchors, each a list of ten aliases of the one before (10**levels leaves)."""
    lines = [f'{indent}a0: &a0 [{", ".join(["lol"] * 10)}]']
    return lines + [f"{indent}a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * 10)}]" for i in range(1, levels + 1)]


def bomb(name: str = "bomb") -> str:
    """An alias bomb behavior: the aliases sit in userdata, which the old loader expanded in full."""
    lines = [f"behavior: {name}", "outcomes: [done]", "userdata:", *laughs(indent="  ")]
    lines += ["states:", "  S:", f"    class: {LOG}", "    parameters: {text: hi}", "    transitions: {done: done}"]
    return "\n".join(lines) + "\n"


# --- part 1: remote names read only the search path ----------------------------------------------------------


@pytest.fixture
def cwd_with_secret(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working directory holding files a remote name could point at, and a separate search path."""
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    (cwd / "notes").write_text(f"{SECRET}\n")
    (cwd / "notes.txt").write_text(f"{SECRET}: 1\n")
    (cwd / "stolen.yaml").write_text(f"behavior: stolen\n{SECRET}: 1\n")
    search = tmp_path / "search"
    search.mkdir()
    (search / "hello.yaml").write_text(chain(1, "hello"))
    monkeypatch.chdir(cwd)
    return search


@pytest.mark.parametrize("name", ["notes", "notes.txt", "stolen", "stolen.yaml", "../cwd/notes", str(Path.cwd())])
def test_a_remote_name_never_reads_the_working_directory(cwd_with_secret: Path, name: str) -> None:
    with pytest.raises(ConfigError) as info:
        load_named_behavior(name, search_path=[cwd_with_secret])
    assert SECRET not in str(info.value)
    with pytest.raises(ConfigError) as info:
        declared_parameter_names(BehaviorSource(name, trusted=False), [cwd_with_secret])
    assert SECRET not in str(info.value)


def test_an_unknown_remote_name_lists_the_valid_names_only(cwd_with_secret: Path) -> None:
    with pytest.raises(ConfigError) as info:
        load_named_behavior("notes", search_path=[cwd_with_secret])
    assert "'notes' is not valid (valid: hello)" in str(info.value)


def test_a_bare_name_is_a_search_path_name_even_when_a_file_of_that_name_is_in_the_cwd(cwd_with_secret: Path) -> None:
    # The old loader read ./notes (Path.is_file() before the name lookup) and echoed its first line:
    # "notes:1: a behavior file must be a mapping, got the value 's3cret-...'".
    with pytest.raises(ConfigError) as info:
        load_behavior("notes", search_path=[cwd_with_secret])
    assert SECRET not in str(info.value)
    assert "valid: hello" in str(info.value)
    assert load_named_behavior("hello", search_path=[cwd_with_secret]).name == "hello"


def test_a_local_source_may_still_be_a_file_path(tmp_path: Path) -> None:
    (tmp_path / "hello.yaml").write_text(chain(1, "hello"))
    assert load_behavior(tmp_path / "hello.yaml").name == "hello"
    assert load_behavior(str(tmp_path / "hello.yaml")).name == "hello"
    assert BehaviorSource.local("hello").is_file is False
    assert BehaviorSource.local("dir/hello").is_file is True
    assert BehaviorSource.remote("hello").trusted is False


def test_a_300_character_name_is_refused_typed(tmp_path: Path) -> None:
    name = "a" * 300  # the old lookup raised OSError ENAMETOOLONG from Path.is_file()
    for load in (lambda: load_named_behavior(name, search_path=[tmp_path]),
                 lambda: load_behavior(name, search_path=[tmp_path]),
                 lambda: find_behavior(name, [tmp_path])):
        with pytest.raises(ConfigError, match=rf"300 characters long \(at most {MAX_NAME_CHARS}\)"):
            load()
    with pytest.raises(ConfigError, match="must be a string"):
        BehaviorSource.remote(7)  # type: ignore[arg-type]


def test_list_behaviors_skips_what_is_not_a_behavior_file(tmp_path: Path) -> None:
    (tmp_path / "ok.yaml").write_text(chain(1, "ok"))
    (tmp_path / "dir.yaml").mkdir()
    (tmp_path / "bad name.yaml").write_text(chain(1, "x"))
    os.mkfifo(tmp_path / "fifo.yaml")
    assert list(list_behaviors([tmp_path])) == ["ok"]
    with pytest.raises(ConfigError, match="not valid"):
        find_behavior("fifo", [tmp_path])  # a FIFO would block the reader forever


# --- part 2: bounded loads ----------------------------------------------------------------------------------


def test_the_alias_bomb_is_refused_fast_naming_the_limit(tmp_path: Path) -> None:
    (tmp_path / "bomb.yaml").write_text(bomb())
    assert len(bomb()) < 800  # about the 760 bytes
    script = textwrap.dedent(f"""
        import json, time
        from flex_nav.behavior.yaml_loader import load_named_behavior
        from flex_nav.exceptions import FlexNavError
        start = time.monotonic()
        try:
            load_named_behavior("bomb", search_path=[{str(tmp_path)!r}])
            out = {{"error": None}}
        except FlexNavError as err:
            out = {{"error": type(err).__name__, "message": str(err), "limit": getattr(err, "limit", None)}}
        out["elapsed_s"] = time.monotonic() - start
        print("RESULT " + json.dumps(out))
    """)
    outcome = run_command_bounded([sys.executable, "-c", script], dict(os.environ), BOMB_PROCESS_BOUND_S)
    line = next(line for line in outcome.output.splitlines() if line.startswith("RESULT "))
    result = json.loads(line[len("RESULT "):])
    assert result["error"] == "BehaviorLoadLimitError", result
    assert result["limit"] == "max_yaml_nodes"
    assert f"max_yaml_nodes={DEFAULT_LIMITS.max_yaml_nodes}" in result["message"]
    assert result["elapsed_s"] < BOMB_LOAD_BOUND_S, result


def test_aliases_recursion_and_nesting_are_bounded(tmp_path: Path) -> None:
    many = "behavior: many\noutcomes: [done]\nuserdata:\n  a: &a 1\n  b: [" + ", ".join(["*a"] * 1001) + "]\n"
    with pytest.raises(BehaviorLoadLimitError, match=r"more than 1000 alias references .*max_aliases=1000") as info:
        load_behavior_text(many + "states: {}\n", "many.yaml")
    assert info.value.limit == "max_aliases"
    with pytest.raises(BehaviorLoadError, match="recursive data"):
        load_behavior_text("behavior: r\nuserdata: {a: &a [*a]}\noutcomes: [done]\nstates: {}\n", "r.yaml")
    deep = "behavior: d\nuserdata: {a: " + "[" * 5000 + "]" * 5000 + "}\noutcomes: [done]\nstates: {}\n"
    with pytest.raises(BehaviorLoadLimitError, match="max_yaml_depth=64"):  # the old loader: RecursionError
        load_behavior_text(deep, "d.yaml")
    # aliases that nest a 40-level list inside another 40 levels: each text is shallow, the expansion is not
    nested = "[" * 40 + "1" + "]" * 40
    stacked = f"behavior: s\nuserdata:\n  a: &a {nested}\n  b: {'[' * 39}*a{']' * 39}\noutcomes: [done]\nstates: {{}}\n"
    with pytest.raises(BehaviorLoadLimitError, match=r"aliases expanded.*max_yaml_depth=64"):
        load_behavior_text(stacked, "s.yaml")


def test_an_oversize_file_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "big.yaml"
    path.write_text(chain(1, "big") + "#" * DEFAULT_LIMITS.max_bytes + "\n")  # a valid behavior, padded
    started = time.monotonic()
    with pytest.raises(BehaviorLoadLimitError, match=rf"larger than {DEFAULT_LIMITS.max_bytes} bytes") as info:
        load_behavior(path)
    assert info.value.limit == "max_bytes"
    assert time.monotonic() - started < 5.0


def test_included_files_count_against_the_byte_and_state_limits(tmp_path: Path) -> None:
    (tmp_path / "inner.yaml").write_text(chain(5, "inner"))
    outer = ("behavior: outer\noutcomes: [done]\nstates:\n"
             + "".join(f"  I{i}:\n    behavior: inner\n    transitions: {{done: {f'I{i + 1}' if i < 3 else 'done'}}}\n"
                       for i in range(4)))
    (tmp_path / "outer.yaml").write_text(outer)
    assert load_behavior(tmp_path / "outer.yaml").name == "outer"  # 4 + 4 * 5 = 24 states
    with pytest.raises(BehaviorLoadLimitError, match="more than 20 states") as info:
        load_behavior(tmp_path / "outer.yaml", limits=LoadLimits(max_states=20))
    assert info.value.file == str(tmp_path / "inner.yaml")
    small = len(outer) + 2 * len(chain(5, "inner"))
    with pytest.raises(BehaviorLoadLimitError, match=f"max_bytes={small}"):
        load_behavior(tmp_path / "outer.yaml", limits=LoadLimits(max_bytes=small))


def test_too_many_states_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "big.yaml"
    path.write_text(chain(DEFAULT_LIMITS.max_states + 1))
    with pytest.raises(BehaviorLoadLimitError, match=rf"more than {DEFAULT_LIMITS.max_states} states") as info:
        load_behavior(path)
    assert (info.value.limit, info.value.value) == ("max_states", DEFAULT_LIMITS.max_states)
    path.write_text(chain(DEFAULT_LIMITS.max_states))
    assert load_behavior(path).name == "big"


def test_include_depth_is_bounded(tmp_path: Path) -> None:
    depth = DEFAULT_LIMITS.max_include_depth + 1
    for i in range(depth + 1):
        inner = (f"  S:\n    behavior: b{i + 1}\n    transitions: {{done: done}}\n" if i < depth
                 else f"  S:\n    class: {LOG}\n    parameters: {{text: x}}\n    transitions: {{done: done}}\n")
        (tmp_path / f"b{i}.yaml").write_text(f"behavior: b{i}\noutcomes: [done]\nstates:\n{inner}")
    with pytest.raises(BehaviorLoadLimitError, match=r"nested more than 16 deep.*max_include_depth=16"):
        load_behavior("b0", search_path=[tmp_path])
    assert load_behavior("b1", search_path=[tmp_path]).name == "b1"  # 16 levels below b1: within the limit


def test_the_load_time_is_bounded(tmp_path: Path) -> None:
    (tmp_path / "hello.yaml").write_text(chain(3, "hello"))
    with pytest.raises(BehaviorLoadLimitError, match="took longer than 1e-09 s") as info:
        load_behavior(tmp_path / "hello.yaml", limits=LoadLimits(max_load_s=1e-9))
    assert info.value.limit == "max_load_s"


def test_a_non_utf8_file_is_refused_typed(tmp_path: Path) -> None:
    path = tmp_path / "latin.yaml"
    path.write_bytes(b"behavior: latin\ndescription: caf\xe9 " + SECRET.encode() + b"\noutcomes: [done]\nstates: {}\n")
    for load in (lambda: load_behavior(path), lambda: declared_parameter_names(path),
                 lambda: load_named_behavior("latin", search_path=[tmp_path])):
        with pytest.raises(BehaviorLoadError, match=r"latin.yaml:2: the file is not UTF-8 text") as info:
            load()
        assert SECRET not in str(info.value)


def test_files_that_are_not_regular_are_refused(tmp_path: Path) -> None:
    (tmp_path / "dir.yaml").mkdir()
    with pytest.raises(BehaviorLoadError, match="not a regular file"):
        load_behavior(tmp_path / "dir.yaml")


class Exploding(State):
    """A state class whose constructor raises something that is not a FlexNavError."""

    def __init__(self) -> None:
        raise RuntimeError("boom")


def test_any_exception_of_a_load_becomes_a_typed_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    module = types.ModuleType("hostile_states_for_test")
    module.Exploding = Exploding  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "hostile_states_for_test", module)
    text = ("behavior: x\noutcomes: [done]\nstates:\n  S:\n    class: hostile_states_for_test.Exploding\n"
            "    transitions: {done: done}\n")
    with pytest.raises(BehaviorLoadError, match="the load failed: RuntimeError: boom") as info:
        load_behavior_text(text, "x.yaml")
    assert isinstance(info.value.__cause__, RuntimeError)


def test_the_shipped_behaviors_load_well_within_the_limits() -> None:
    """The margin the defaults leave: every shipped behavior loads with the size, node, alias and state limits
    divided by ten and the nesting limits by four (largest shipped: 17 876 bytes, 1 268 nodes, 43 states,
    10 levels, 3 files deep)."""
    d = DEFAULT_LIMITS
    tight = dataclasses.replace(d, max_bytes=d.max_bytes // 10, max_yaml_nodes=d.max_yaml_nodes // 10,
                                max_aliases=d.max_aliases // 10, max_states=d.max_states // 10,
                                max_yaml_depth=d.max_yaml_depth // 4, max_include_depth=d.max_include_depth // 4)
    names = sorted(list_behaviors([BEHAVIORS]))
    assert len(names) >= 10
    for name in names:
        assert load_behavior(name, search_path=[BEHAVIORS], limits=tight).name == name


def test_limits_are_validated() -> None:
    with pytest.raises(ConfigError, match="load limit max_states must be a positive number, got 0"):
        LoadLimits(max_states=0)


def test_command_values_are_parsed_within_the_limits() -> None:
    assert safe_load_bounded("[1, {a: b}]", "argument x") == [1, {"a": "b"}]
    assert safe_load_bounded("", "argument x") is None
    with pytest.raises(BehaviorLoadLimitError, match="max_yaml_nodes"):
        safe_load_bounded("\n".join(laughs()), "argument x")
    with pytest.raises(BehaviorLoadError, match="not valid YAML"):
        safe_load_bounded("[unclosed", "argument x")
    with pytest.raises(FlexNavError, match="max_bytes"):
        safe_load_bounded("x" * (DEFAULT_LIMITS.max_bytes + 1), "argument x")
