"""ruff, mypy, the layer contracts and the ros marker as tests, so the single pytest run also fails on lint or
type errors, a broken layer, or a test that starts a master without ``@pytest.mark.ros``."""

from __future__ import annotations

import ast
import os
import sys
import textwrap
from typing import List, Sequence, Set

import pytest
from harness import REPO_ROOT, run_command_bounded

VENV_BIN = REPO_ROOT / ".venv" / "bin"
TEST_DIR = REPO_ROOT / "test"
# The test folders mypy checks, with test/ as a root as for pytest (pythonpath; unit.perception.scan_synth
# resolves), under pyproject's override for test modules (bodies checked, annotations optional); the files of
# test/ and test/unit themselves too. Not yet, type errors left (add a folder once mypy is clean on it):
# the rostest nodes (test/rostest, which would be a root of its own: a node runs with its folder on sys.path;
# MYPYPATH=src:test/rostest:test/data/compat). unit/compat imports the example FlexBE states of test/data/compat.
# A module of a folder not yet clean as a whole can be listed alone.
MYPY_CLEAN_TEST_DIRS = [
    "system", "unit/behavior", "unit/compat", "unit/eval", "unit/follow", "unit/localization", "unit/nav",
    "unit/perception", "unit/ros", "unit/sim", "unit/states", "unit/mapping", "unit/console",
]
MYPY_TEST_TARGETS = [
    *sorted(str(p.relative_to(REPO_ROOT)) for p in [*TEST_DIR.glob("*.py"), *(TEST_DIR / "unit").glob("*.py")]),
    *(f"test/{folder}" for folder in MYPY_CLEAN_TEST_DIRS),
]


def test_ruff_clean() -> None:
    outcome = run_command_bounded([str(VENV_BIN / "ruff"), "check", "--no-cache", "."], env=_env(), timeout_s=300)
    assert outcome.returncode == 0, f"ruff found problems:\n{outcome.output[-8000:]}"


@pytest.mark.parametrize(
    ("targets", "roots"),
    [
        (["-p", "flex_nav", "-p", "flex_nav_states", "-p", "flex_nav_sim", "-p", "tools"], ["src"]),
        # scripts, not a package
        (sorted(str(p.relative_to(REPO_ROOT)) for p in (REPO_ROOT / "bench").glob("*.py")), ["src"]),
        # modules named from their roots (test/unit/nav/x.py is unit.nav.x), as pytest's importlib mode imports them
        (["--explicit-package-bases", *MYPY_TEST_TARGETS], ["src", "test", "test/data/compat"]),
    ],
    ids=["packages", "bench", "tests"],
)
def test_mypy_clean(targets: list[str], roots: list[str]) -> None:
    outcome = run_command_bounded([sys.executable, "-m", "mypy", *targets], env=_env(roots), timeout_s=600)
    assert outcome.returncode == 0, f"mypy found problems:\n{outcome.output[-8000:]}"
    assert "Success" in outcome.output


def test_layers_kept() -> None:
    # the contracts in pyproject.toml ([tool.importlinter]): the pure core imports no rospy and nothing of the ROS
    # side; applications, test harness, nodes and adapters only import downwards
    outcome = run_command_bounded([str(VENV_BIN / "lint-imports"), "--no-cache"], env=_env(), timeout_s=300)
    assert outcome.returncode == 0, f"import-linter found a layer violation:\n{outcome.output[-8000:]}"
    assert "0 broken" in outcome.output


# What starts a master in a test: the class, the fixture, rostest, or a roscore command line
MASTER_SIGNS = frozenset({"PrivateMaster", "ros_master", "run_rostest", "roscore"})


def test_tests_that_start_a_master_carry_the_ros_marker() -> None:
    # `-m "not ros"` must run nothing that needs a master (rostest nodes under test/rostest run under one already)
    unmarked = [
        f"{path.relative_to(REPO_ROOT)}::{name}"
        for path in sorted(TEST_DIR.rglob("test_*.py")) if path.parent.name not in ("rostest", "data")
        for name in unmarked_master_tests(path.read_text())
    ]
    assert unmarked == [], f"these tests start a master but lack @pytest.mark.ros: {unmarked}"


def test_the_marker_check_finds_unmarked_masters() -> None:
    source = textwrap.dedent('''
        import pytest
        from flex_nav.testing.private_master import PrivateMaster

        @pytest.fixture
        def own_master(tmp_path):
            with PrivateMaster(ros_home=tmp_path) as master:
                yield master

        def start():
            return PrivateMaster().start()

        def test_direct(): PrivateMaster().start()
        def test_shared_fixture(ros_master): pass
        def test_own_fixture(own_master): pass
        def test_helper(): start()
        def test_roscore(): run(["roscore", "-p", "1"])
        @pytest.mark.usefixtures("ros_master")
        def test_usefixtures(): pass
        def test_pure(): assert 1 + 1 == 2

        @pytest.mark.ros
        def test_marked(ros_master): pass

        class TestGroup:
            def test_method(self, ros_master): pass

        @pytest.mark.ros
        class TestMarkedGroup:
            def test_method(self, ros_master): pass
    ''')
    assert unmarked_master_tests(source) == [
        "test_direct", "test_shared_fixture", "test_own_fixture", "test_helper", "test_roscore", "test_usefixtures",
        "TestGroup::test_method",
    ]
    assert unmarked_master_tests("import pytest\npytestmark = [pytest.mark.ros]\n" + source) == []


def unmarked_master_tests(source: str) -> List[str]:
    """The tests in ``source`` (a test module) that start a master, or use a fixture or a module-level helper that
    does, without the ``ros`` marker on themselves, their class or the module (``pytestmark``)."""
    tree = ast.parse(source)
    functions = {node.name: node for node in tree.body if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))}
    signs = {name: _signs(node) for name, node in functions.items()}
    starting: Set[str] = set(MASTER_SIGNS)
    while True:  # a helper or fixture that starts a master makes its users start one
        more = {name for name, used in signs.items() if used & starting} - starting
        if not more:
            break
        starting |= more
    if any(_marks_ros(value) for value in _pytestmarks(tree.body)):
        return []
    unmarked = []
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name.startswith("test"):
            if _signs(node) & starting and not any(_marks_ros(d) for d in node.decorator_list):
                unmarked.append(node.name)
        elif isinstance(node, ast.ClassDef) and node.name.startswith("Test"):
            class_marked = any(_marks_ros(d) for d in [*node.decorator_list, *_pytestmarks(node.body)])
            for method in node.body:
                if (isinstance(method, (ast.FunctionDef, ast.AsyncFunctionDef)) and method.name.startswith("test")
                        and _signs(method) & starting and not class_marked
                        and not any(_marks_ros(d) for d in method.decorator_list)):
                    unmarked.append(f"{node.name}::{method.name}")
    return unmarked


def _signs(node: ast.AST) -> Set[str]:
    """The names, attributes, parameters and string constants in ``node`` (with its decorators)."""
    found: Set[str] = set()
    for sub in ast.walk(node):
        if isinstance(sub, ast.Name):
            found.add(sub.id)
        elif isinstance(sub, ast.Attribute):
            found.add(sub.attr)
        elif isinstance(sub, ast.arg):
            found.add(sub.arg)
        elif isinstance(sub, ast.Constant) and isinstance(sub.value, str):
            found.add(sub.value)
    return found


def _pytestmarks(body: List[ast.stmt]) -> List[ast.expr]:
    """The marks assigned to ``pytestmark`` in a module's or class's ``body`` (one, or a list or tuple of them)."""
    marks: List[ast.expr] = []
    for node in body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "pytestmark" for t in node.targets):
            value = node.value
            marks.extend(value.elts if isinstance(value, (ast.List, ast.Tuple)) else [value])
    return marks


def _marks_ros(expr: ast.expr) -> bool:
    """``pytest.mark.ros`` (or ``mark.ros``)."""
    return ast.unparse(expr.func if isinstance(expr, ast.Call) else expr).split(".")[-2:] == ["mark", "ros"]


def _env(roots: Sequence[str] = ("src",)) -> dict[str, str]:
    env = dict(os.environ)
    env["MYPYPATH"] = os.pathsep.join(str(REPO_ROOT / root) for root in roots)
    return env
