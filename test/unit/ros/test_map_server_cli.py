"""map_server fails at once, with map_io's reason and exit status 1, on a bad or missing map file."""

import os
import sys
from pathlib import Path

import pytest
from harness import REPO_ROOT, run_command_bounded


def run_map_server(*args: str):
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}:{env.get('PATH', '')}"
    env["ROS_MASTER_URI"] = "http://127.0.0.1:9/"  # nothing there: the node must not get that far
    return run_command_bounded([sys.executable, str(REPO_ROOT / "scripts" / "map_server"), *args], env, 30.0)


def test_missing_file(tmp_path):
    outcome = run_map_server(str(tmp_path / "nope.yaml"))
    assert outcome.returncode == 1
    assert f"map file {tmp_path / 'nope.yaml'} does not exist" in outcome.output


def test_bad_field(tmp_path):
    (tmp_path / "bad.yaml").write_text("image: x.pgm\nresolution: -1\norigin: [0, 0, 0]\nnegate: 0\n"
                                       "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    outcome = run_map_server(str(tmp_path / "bad.yaml"))
    assert outcome.returncode == 1
    assert "resolution" in outcome.output and "bad.yaml" in outcome.output


@pytest.mark.parametrize("args", [(), ("a.yaml", "b.yaml")])
def test_usage(args):
    outcome = run_map_server(*args)
    assert outcome.returncode == 1
    assert "usage: rosrun flex_nav map_server MAP.yaml" in outcome.output
