"""The engine is pure Python: importing every module of flex_nav.behavior never imports rospy."""

from __future__ import annotations

import pkgutil
import subprocess
import sys

import flex_nav.behavior


def test_no_module_of_the_engine_imports_rospy():
    modules = [f"flex_nav.behavior.{m.name}" for m in pkgutil.iter_modules(flex_nav.behavior.__path__)]
    assert "flex_nav.behavior.yaml_loader" in modules and "flex_nav.behavior.executor" in modules
    code = (
        "import sys\n"
        + "".join(f"import {m}\n" for m in modules)
        + ("print(sorted(n for n in sys.modules if n.split('.')[0] in ('rospy', 'rosgraph', 'genpy', 'actionlib')))")
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=True)
    assert out.stdout.strip() == "[]"
