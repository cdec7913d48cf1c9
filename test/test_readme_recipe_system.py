"""The README's shell recipe ("Using it from a shell"), run as a newcomer would: in tmux, in fresh login-less bash
shells (no venv, no ROS variables), the commands copied from the README's code blocks -- the first shell starts
roscore, the simulator and the robot in the background; a second shell repeats the two set-up lines and watches
the runner; the first sends the goal and approves (``approve-next`` as often as the README says the Flex Planner
asks); the robot arrives; ``kill -INT $(jobs -p)`` stops everything. Only the master's port is changed, to a free
one. A README edit that breaks a command fails this test."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import time
from pathlib import Path
from typing import Callable, Iterator, List

import psutil  # type: ignore[import-untyped]  # a dependency (requirements.txt) without stubs
import pytest
import rosgraph

from flex_nav.testing.private_master import free_port

REPO = Path(__file__).resolve().parents[1]
SECTION = "## Using it from a shell"
README_PORT = "11411"  # the port the README's recipe uses; replaced by a free one
READY_TIMEOUT_S = 120.0  # [s] wall: roscore, the simulator and the robot's stack up
ARRIVAL_TIMEOUT_S = 240.0  # [s] wall: the goal approved and reached at rtf 1
STOP_TIMEOUT_S = 40.0  # [s] wall: everything gone after kill -INT
MAX_APPROVE_NEXT = 8  # the README: three are asked for (the plan, the replan, "continue"); a timed-out one is repeated
CLEAN_SHELL = ["env", "-i", f"HOME={os.environ.get('HOME', '/root')}", "PATH=/usr/local/bin:/usr/bin:/bin",
               "TERM=xterm", "bash", "--noprofile", "--norc"]


def recipe() -> tuple[List[str], List[str], str]:
    """(first shell's set-up block, the goal block, the second shell's watch command) from the README."""
    text = (REPO / "README.md").read_text()
    section = text[text.index(SECTION):]
    section = section[:section.index("\n## ", len(SECTION))]
    blocks = re.findall(r"```sh\n(.*?)```", section, flags=re.S)
    assert len(blocks) >= 2, f"the README's '{SECTION}' lost its code blocks"
    watch = re.search(r"`(rosrun flex_nav operator [^`]*watch)`", section)
    assert watch is not None, "the README no longer says how to watch the runner from a second shell"
    return blocks[0].splitlines(), blocks[1].splitlines(), watch.group(1)


class Tmux:
    """A tmux server of the test's own (its socket name), windows running clean shells in the repository."""

    def __init__(self, name: str) -> None:
        self.base = ["tmux", "-L", name, "-f", "/dev/null"]
        self.run("new-session", "-d", "-s", "recipe", "-x", "220", "-y", "60", "-c", str(REPO),
                 shlex.join(CLEAN_SHELL))

    def run(self, *args: str) -> str:
        return subprocess.run([*self.base, *args], capture_output=True, text=True, timeout=30, check=True).stdout

    def new_window(self, name: str) -> None:
        self.run("new-window", "-t", "recipe", "-n", name, "-c", str(REPO), shlex.join(CLEAN_SHELL))

    def type(self, window: str, line: str) -> None:
        self.run("send-keys", "-t", f"recipe:{window}", "-l", line)
        self.run("send-keys", "-t", f"recipe:{window}", "Enter")

    def screen(self, window: str) -> str:
        return self.run("capture-pane", "-p", "-J", "-S", "-3000", "-t", f"recipe:{window}")

    def kill(self) -> None:
        subprocess.run([*self.base, "kill-server"], capture_output=True, timeout=30, check=False)


def processes_on(port: int) -> List[psutil.Process]:
    """Every process whose environment points at the master on ``port`` (what the recipe started)."""
    uri = f"http://127.0.0.1:{port}/"
    found = []
    for proc in psutil.process_iter():
        try:
            if proc.environ().get("ROS_MASTER_URI") == uri:
                found.append(proc)
        except psutil.Error:
            continue
    return found


def published(uri: str) -> set[str]:
    try:
        return {name for name, _type in rosgraph.Master("/readme_recipe_test", master_uri=uri).getPublishedTopics("/")}
    except (OSError, rosgraph.MasterException):  # the master is not up (yet): nothing is published
        return set()


def wait_for(condition: Callable[[], bool], timeout_s: float, what: str, screen: Iterator[str]) -> None:
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"{what} within {timeout_s:.0f} s; the shells showed:\n" + "\n".join(screen)[-6000:])
        time.sleep(1.0)


@pytest.mark.ros
def test_the_readme_recipe_runs_in_two_shells_and_the_robot_arrives() -> None:
    if shutil.which("tmux") is None:
        pytest.fail("tmux is not installed: run tools/install.sh")
    setup, goal, watch = recipe()
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    setup = [line.replace(README_PORT, str(port)) for line in setup]
    tmux = Tmux(f"flex_nav_recipe_{port}")

    def screens() -> Iterator[str]:
        for window in ("0", "watch"):
            try:
                yield f"--- shell {window} ---\n" + tmux.screen(window)
            except subprocess.SubprocessError:
                continue

    def leftovers() -> Iterator[str]:
        yield from screens()
        yield "left running: " + ", ".join(" ".join(proc.cmdline()[:3]) for proc in processes_on(port))

    try:
        for line in setup:
            tmux.type("0", line)
        wait_for(lambda: {"/robot1/behavior_runner/status", "/robot1/odom"} <= published(uri), READY_TIMEOUT_S,
                 "the runner and the simulated robot did not come up", screens())
        tmux.new_window("watch")
        for line in setup[:2]:  # "the same two set-up lines first"
            tmux.type("watch", line)
        tmux.type("watch", watch)
        time.sleep(5.0)  # the watcher connected before the goal
        for line in goal:
            tmux.type("0", line)
        sent = sum("approve-next" in line for line in goal)  # the block's own
        deadline = time.monotonic() + ARRIVAL_TIMEOUT_S
        while "--arrived-->" not in tmux.screen("watch"):
            if time.monotonic() > deadline:
                pytest.fail("the robot did not arrive; the shells showed:\n" + "\n".join(screens())[-6000:])
            shell = tmux.screen("0")
            answered = shell.count("approving ") + shell.count("no outcome request")
            if answered >= sent and sent < MAX_APPROVE_NEXT:  # the last one is done: the next, as the README says
                tmux.type("0", "rosrun flex_nav operator --runner /robot1/behavior_runner approve-next")
                sent += 1
            time.sleep(2.0)
        watched = tmux.screen("watch")
        assert "[transition] /GetPath --planned--> ApprovePlan" in watched, watched[-3000:]
        assert "[transition] /ApprovePlan --execute--> Navigate" in watched, watched[-3000:]
        main_shell = tmux.screen("0")
        assert "approving /ApprovePlan" in main_shell, main_shell[-3000:]
        tmux.run("send-keys", "-t", "recipe:watch", "C-c")  # done watching
        tmux.type("0", "kill -INT $(jobs -p)")
        wait_for(lambda: not processes_on(port), STOP_TIMEOUT_S, "kill -INT $(jobs -p) did not stop everything",
                 leftovers())
    finally:
        tmux.kill()
        for proc in processes_on(port):  # whatever a failed run left behind
            try:
                proc.kill()
            except psutil.Error:
                continue
