"""Helper of the rostest nodes that start a node with bad input: it must exit 2 with a message, without a
stack trace, and leave nothing registered with the master."""

import itertools
import os
import subprocess
from pathlib import Path
from typing import List, Tuple

import rosgraph

RUN_TIMEOUT_S = 60.0  # [s] a rejected start must end well within this

_STARTS = itertools.count(1)


def fresh_name(prefix: str) -> str:
    """A node name new in this process, ``prefix_N``: each refused start is checked under a name of its own (what a
    start before it left registered cannot be taken for its own)."""
    return f"{prefix}_{next(_STARTS)}"


def run_refused(test, executable: Path, name: str, *params: str) -> Tuple[str, List]:
    """Run ``executable`` as node ``name`` with ``params``; assert on ``test`` (a unittest.TestCase) that it
    exited 2 without a traceback and left no topic or service registered. Returns (stderr, publishers)."""
    proc = subprocess.run(
        [str(executable), f"__name:={name}", *params],
        capture_output=True,
        text=True,
        timeout=RUN_TIMEOUT_S,
        env=dict(os.environ),
        check=False,
    )
    test.assertEqual(proc.returncode, 2, f"exit {proc.returncode}; stderr:\n{proc.stderr[-2000:]}")
    test.assertNotIn("Traceback", proc.stderr)
    publishers, subscribers, services = rosgraph.Master(f"/{name}_check").getSystemState()
    for topic, nodes in publishers + subscribers + services:  # nothing half-started stays registered
        test.assertNotIn(f"/{name}", nodes, f"{name} still registered on {topic}")
    return proc.stderr, publishers
