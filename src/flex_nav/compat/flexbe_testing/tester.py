"""flexbe_testing.tester: FlexBE's Tester: runs YAML test cases against states and behaviors (see the package)."""

from __future__ import annotations

import re
import unittest
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, Mapping, Optional, Type

from flex_nav.behavior.yaml_limits import safe_load_bounded
from flex_nav.compat.flexbe_core.core.user_data import UserData
from flex_nav.compat.flexbe_testing.data_provider import DataProvider
from flex_nav.compat.flexbe_testing.logger import Logger
from flex_nav.compat.flexbe_testing.test_context import TestContext
from flex_nav.compat.flexbe_testing.test_interface import DEFAULT_TIME_LIMIT_S, TestInterface

Check = Callable[[unittest.TestCase], None]


def load_test_cases(paths: Iterable[Path]) -> Dict[str, Any]:
    """FlexBE's test case files by name (the file name without its suffix), parsed with a bounded safe loader."""
    cases: Dict[str, Any] = {}
    for path in paths:
        cases[Path(path).stem] = safe_load_bounded(Path(path).read_text(encoding="utf-8"), str(path))
    return cases


class Tester:
    """Runs test cases; keeps one unittest check per result (``test_<name>_pass``, ``_outcome``, ``_output_<key>``)."""

    __test__ = False  # not a pytest test class

    def __init__(self) -> None:
        self._tests: Dict[str, Check] = {}
        self.failures: Dict[str, str] = {}  # case name -> why it failed

    def run_test(self, name: str, config: Any) -> int:  # noqa: PLR0911  (one early return per failure kind)
        """Run one case; 1 if it passed, else 0 (the reason is in ``failures[name]``)."""
        try:
            self._verify_config(config)
        except AssertionError as err:
            return self._fail(name, "Invalid", f"invalid test specification: {err}", invalid=True)
        config = dict(config)
        if "name" in config:  # a behavior given by its name: module <name>_sm, class <Name>SM
            config["path"] += "." + re.sub(r"[^\w]", "_", str(config["name"]).lower()) + "_sm"
            config["class"] = re.sub(r"[^\w]", "", str(config["name"])) + "SM"
        import_only = bool(config.get("import_only", False))
        Logger.print_title(name, config["class"], None if import_only else config["outcome"])
        try:
            interface = TestInterface(config["path"], config["class"])
        except Exception as err:
            return self._fail(name, None, f"unable to import {config['class']} ({config['path']}): {err}")
        if import_only:
            return self._succeed(name)
        for unsupported in ("launch", "data"):
            if unsupported in config:
                return self._fail(name, None, f"'{unsupported}' is not supported by flex_nav's flexbe_testing")
        data = DataProvider()
        context = TestContext()
        with context:
            params = {key: data.parse(value) for key, value in dict(config.get("params") or {}).items()}
            try:
                interface.instantiate(params)
            except Exception as err:
                return self._fail(name, None, f"unable to instantiate {config['class']} with {params}: {err}")
            userdata = UserData()
            for key, value in dict(config.get("input") or {}).items():
                userdata[key] = data.parse(value)
            expected = {key: data.parse(value) for key, value in dict(config.get("output") or {}).items()}
            time_limit_s = float(config.get("time_limit", DEFAULT_TIME_LIMIT_S))
            try:
                outcome = interface.execute(userdata, spin_cb=context.spin_once, time_limit_s=time_limit_s)
            except Exception as err:
                return self._fail(name, None, f"failed to execute {config['class']}: {type(err).__name__}: {err}")
        return self._evaluate(name, config["outcome"], outcome, expected, userdata)

    def _evaluate(self, name: str, wanted: Any, outcome: Any, expected: Mapping[str, Any], userdata: UserData) -> int:
        self._tests[f"test_{name}_outcome"] = _equal(outcome, wanted, "Outcome")
        problems = []
        if outcome != wanted:
            problems.append(f"wrong outcome: {outcome!r} (expected {wanted!r})")
        for key, value in expected.items():
            if key not in userdata:
                problems.append(f"no result for {key}")
                continue
            self._tests[f"test_{name}_output_{key}"] = _equal(userdata[key], value, f"Output {key}")
            if userdata[key] != value:
                problems.append(f"wrong result for {key}: {userdata[key]!r} != {value!r}")
        if problems:
            return self._fail(name, None, "; ".join(problems))
        Logger.print_positive(f"correctly returned outcome {outcome}")
        return self._succeed(name)

    def _succeed(self, name: str) -> int:
        Logger.print_result(name, True)
        self._tests[f"test_{name}_pass"] = _passed(True, "")
        return 1

    def _fail(self, name: str, title: Optional[str], reason: str, invalid: bool = False) -> int:
        if title is not None:
            Logger.print_title(name, title)
        Logger.print_failure(reason)
        Logger.print_result(name, False)
        self.failures[name] = reason
        self._tests[f"test_{name}_pass"] = _passed(False, ("Test config is invalid: " if invalid else "") + reason)
        return 0

    @staticmethod
    def _verify_config(config: Any) -> None:
        if not isinstance(config, dict):
            raise AssertionError(f"config needs to be a dictionary but is: {config!r}")
        assert "path" in config, "missing 'path'"
        assert "class" in config or "name" in config, "missing 'class' (or 'name' of a behavior)"
        assert "outcome" in config or config.get("import_only", False), "missing 'outcome'"

    # --- unittest interface ----------------------------------------------------------------------------------
    def test_case_class(self, test_pkg: str = "flexbe") -> Type[unittest.TestCase]:
        """A unittest TestCase with one test method per recorded check."""
        return type(f"{test_pkg}_test_class", (unittest.TestCase,), dict(self._tests))

    def perform_rostest(self, test_pkg: str) -> None:
        """Run the recorded checks as one unittest suite (FlexBE hands them to rosunit)."""
        suite = unittest.defaultTestLoader.loadTestsFromTestCase(self.test_case_class(test_pkg))
        unittest.TextTestRunner(verbosity=2).run(suite)


def _equal(value: Any, expected: Any, what: str) -> Check:
    def check(case: unittest.TestCase) -> None:
        case.assertEqual(value, expected, f"{what} {value!r} does not match expected {expected!r}")

    return check


def _passed(passed: bool, reason: str) -> Check:
    def check(case: unittest.TestCase) -> None:
        case.assertTrue(passed, reason or "Did not pass configured tests.")

    return check


__all__ = ["Tester", "load_test_cases"]
