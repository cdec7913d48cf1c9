#!/usr/bin/env python3
"""Generate flex_nav's Python action/message/service classes without catkin.

Reads ``action/*.action``, expands each into its eight messages with actionlib_msgs' genaction
(into ``build/msg``), copies the plain messages ``msg/*.msg`` beside them, and generates Python
modules into ``src/flex_nav/msg`` with genpy, one file at a time (``genpy.generator.reset_var()``
before each, so the output matches catkin's byte for byte), and the services ``srv/*.srv`` into
``src/flex_nav/srv`` the same way. Skips all work when the inputs and
genpy are unchanged since the last run (a stamp file holds their hash). Exit status 0 on success,
2 with a message on failure.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
ACTION_DIR = REPO / "action"
MSG_DIR = REPO / "msg"  # plain messages (e.g. the simulator's bumper and event messages)
SRV_DIR = REPO / "srv"  # services (e.g. the simulator's teleport)
BUILD_DIR = REPO / "build" / "msg"
OUT_DIR = REPO / "src" / "flex_nav" / "msg"
SRV_OUT_DIR = REPO / "src" / "flex_nav" / "srv"
STAMP = OUT_DIR / ".inputs.sha256"
PACKAGE = "flex_nav"
GENACTION = Path("/usr/lib/actionlib_msgs/genaction.py")
SEARCH_PATH = {
    PACKAGE: [str(BUILD_DIR)],
    "std_msgs": ["/usr/share/std_msgs/msg"],
    "geometry_msgs": ["/usr/share/geometry_msgs/msg"],
    "nav_msgs": ["/usr/share/nav_msgs/msg"],
    "actionlib_msgs": ["/usr/share/actionlib_msgs/msg"],
}


def fail(message: str) -> int:
    print(f"[flex_nav gen_actions] ERROR: {message}", file=sys.stderr)
    return 2


def inputs_hash(actions: list[Path]) -> str:
    import genpy

    digest = hashlib.sha256()
    digest.update(str(getattr(genpy, "__file__", "")).encode())
    for path in [*actions, *sorted(MSG_DIR.glob("*.msg")), *sorted(SRV_DIR.glob("*.srv")), Path(__file__)]:
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


def generate_messages(actions: list[Path]) -> str:
    """Expand the actions and copy the plain messages into BUILD_DIR, generate them all into OUT_DIR, one file at
    a time; the problem, or '' on success."""
    import genpy.generator

    BUILD_DIR.mkdir(parents=True, exist_ok=True)
    for old in BUILD_DIR.glob("*.msg"):
        old.unlink()
    for action in actions:
        proc = subprocess.run(
            [sys.executable, str(GENACTION), str(action), "-o", str(BUILD_DIR)],
            capture_output=True, text=True, timeout=60, check=False,
        )
        if proc.returncode != 0:
            return f"genaction failed on {action.name}: {proc.stderr.strip() or proc.stdout.strip()}"

    for msg in sorted(MSG_DIR.glob("*.msg")):
        shutil.copyfile(msg, BUILD_DIR / msg.name)
    return generate_python(genpy.generator.MsgGenerator(), sorted(BUILD_DIR.glob("*.msg")), OUT_DIR)


def generate_services() -> str:
    """Generate ``srv/*.srv`` into SRV_OUT_DIR; the problem, or '' on success."""
    import genpy.generator

    return generate_python(genpy.generator.SrvGenerator(), sorted(SRV_DIR.glob("*.srv")), SRV_OUT_DIR)


def generate_python(generator: Any, sources: list[Path], out_dir: Path) -> str:
    """Replace the generated modules of ``out_dir`` by those of ``sources``, one file at a time (genpy's state
    reset before each, as catkin does), and its ``__init__.py``; the problem, or '' on success."""
    import genpy.generate_initpy
    import genpy.generator

    out_dir.mkdir(parents=True, exist_ok=True)
    for old in out_dir.glob("_[A-Z]*.py"):
        old.unlink()
    for source in sources:
        genpy.generator.reset_var()
        status = generator.generate_messages(PACKAGE, [str(source)], str(out_dir), SEARCH_PATH)
        if status:
            return f"genpy failed on {source.name} (status {status})"
    status = genpy.generate_initpy.write_modules(str(out_dir))
    return f"writing {out_dir}/__init__.py failed (status {status})" if status else ""


def main() -> int:
    actions = sorted(ACTION_DIR.glob("*.action"))
    if not actions:
        return fail(f"no .action files in {ACTION_DIR}")
    try:
        import genpy.generate_initpy  # checked here; generate_messages and generate_services use them
        import genpy.generator  # noqa: F401
    except ImportError as err:
        return fail(f"genpy is not importable ({err}); install Debian's python3-genpy (tools/install.sh does)")
    if not GENACTION.is_file():
        return fail(f"{GENACTION} is missing; install Debian's libactionlib-msgs-dev (tools/install.sh does)")

    want = inputs_hash(actions)
    if (STAMP.is_file() and STAMP.read_text().strip() == want and (OUT_DIR / "__init__.py").is_file()
            and (SRV_OUT_DIR / "__init__.py").is_file()):
        print(f"[flex_nav gen_actions] action classes up to date ({len(actions)} actions)")
        return 0

    problem = generate_messages(actions) or generate_services()
    if problem:
        return fail(problem)
    STAMP.write_text(want + "\n")
    count = len(list(OUT_DIR.glob("_[A-Z]*.py")))
    print(f"[flex_nav gen_actions] generated {count} message modules from {len(actions)} actions into "
          f"{os.path.relpath(OUT_DIR, REPO)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
