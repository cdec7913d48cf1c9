"""The installer's error paths (with fake apt/dpkg/id/sudo on PATH) and its idempotency (for real)."""

from __future__ import annotations

import os
import stat
import subprocess
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
INSTALL = REPO_ROOT / "tools" / "install.sh"
INSTALL_TIMEOUT_S = 300.0  # [s]


def _write_tool(bin_dir: Path, name: str, body: str) -> None:
    path = bin_dir / name
    path.write_text("#!/bin/sh\n" + body + "\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)


def _fake_system(tmp_path: Path, apt_get_body: str, uid: int = 0, sudo_ok: bool = False) -> dict[str, str]:
    """Environment whose PATH starts with fakes: one apt package reported missing, apt-get as scripted."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    # python3-rospy is "not installed"; every other package is installed.
    _write_tool(bin_dir, "dpkg-query", '[ "$3" = python3-rospy ] && exit 1; printf installed')
    _write_tool(bin_dir, "apt-get", apt_get_body)
    _write_tool(bin_dir, "id", f'[ "$1" = -u ] && echo {uid} && exit 0; echo tester')
    _write_tool(bin_dir, "sudo", "exit 0" if sudo_ok else "exit 1")
    env = dict(os.environ)
    env["PATH"] = f"{bin_dir}:{env['PATH']}"
    env["FLEX_NAV_VENV"] = str(tmp_path / "venv-not-created")
    return env


def _run_install(env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(INSTALL)], env=env, capture_output=True, text=True, timeout=INSTALL_TIMEOUT_S, check=False
    )


def _refused(tmp_path: Path, apt_get_body: str, uid: int = 0, sudo_ok: bool = False) -> str:
    """The installer run on ``_fake_system``, which it must refuse (exit 2): what it wrote on stderr."""
    proc = _run_install(_fake_system(tmp_path, apt_get_body, uid, sudo_ok))
    assert proc.returncode == 2, proc.stdout + proc.stderr
    return proc.stderr


def test_not_root_without_sudo_says_what_to_run(tmp_path: Path) -> None:
    stderr = _refused(tmp_path, "exit 0", uid=1000, sudo_ok=False)
    assert "needs root" in stderr
    assert "sudo apt-get install -y python3-rospy" in stderr
    assert "Traceback" not in stderr
    assert not (tmp_path / "venv-not-created").exists(), "nothing after the apt step may run"


def test_held_apt_lock_is_explained(tmp_path: Path) -> None:
    body = (
        'echo "E: Could not get lock /var/lib/dpkg/lock-frontend. It is held by process 4242 (apt-get)" >&2; '
        "exit 100"
    )
    stderr = _refused(tmp_path, body)
    assert "holds the apt lock" in stderr
    assert "FLEX_NAV_APT_LOCK_TIMEOUT" in stderr


def test_no_network_is_explained(tmp_path: Path) -> None:
    body = (
        'echo "W: Failed to fetch http://deb.debian.org/debian/dists/bookworm/InRelease  '
        "Temporary failure resolving 'deb.debian.org'\"; exit 0"
    )
    assert "cannot be reached" in _refused(tmp_path, body)


def test_offline_pip_is_explained(tmp_path: Path) -> None:
    env = dict(os.environ)
    env.update(
        FLEX_NAV_SKIP_APT="1",
        FLEX_NAV_VENV=str(tmp_path / "venv"),
        PIP_NO_INDEX="1",
        PIP_FIND_LINKS="",
        PIP_CONFIG_FILE=os.devnull,
    )
    proc = _run_install(env)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "pip could not download the pinned packages" in proc.stderr
    assert "Traceback" not in proc.stderr.split("[flex_nav install] ERROR")[-1]


def _tree_state(paths: list[Path]) -> dict[str, tuple[int, int]]:
    state = {}
    for root in paths:
        for path in [root, *root.rglob("*")] if root.is_dir() else [root]:
            if path.is_file() and "__pycache__" not in path.parts:
                info = path.stat()
                state[str(path)] = (info.st_mtime_ns, info.st_size)
    return state


@pytest.mark.skipif(not (REPO_ROOT / ".venv").is_dir(), reason="needs the installed .venv")
def test_second_run_changes_nothing() -> None:
    watched = [
        REPO_ROOT / "src" / "flex_nav" / "msg",
        REPO_ROOT / ".venv" / "pyvenv.cfg",
        REPO_ROOT / ".venv" / "bin" / "activate",
        REPO_ROOT / ".venv" / ".flex_nav-requirements.sha256",
    ]
    env = dict(os.environ)
    env.pop("FLEX_NAV_VENV", None)
    first = _run_install(env)
    assert first.returncode == 0, first.stdout + first.stderr
    before = _tree_state(watched)
    second = _run_install(env)
    assert second.returncode == 0, second.stdout + second.stderr
    assert _tree_state(watched) == before
    assert "action classes up to date" in second.stdout
    assert "pinned requirements already installed" in second.stdout
