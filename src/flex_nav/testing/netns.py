"""Two "hosts" on one machine: two network namespaces joined by a veth pair, for split-deployment tests.

Needs root and iproute2 (``ip``); :func:`netns_unavailable_reason` says why it cannot be used here. Each
:class:`NetnsPair` has names unique to the process and the instance, its own /30 subnet (10.231.X.0/30: the
first host .1, the second .2) and ``lo`` up on both sides. Commands run in a namespace through
``ip netns exec`` (which execs in place: the process id is the command's). :meth:`NetnsPair.stop` ends every
process still inside the namespaces, by the ids ``ip netns pids`` lists (what lives there was started there by
the pair's user: roscore's master and rosout run in sessions of their own and would outlive their parent), then
deletes the namespaces; the veth pair goes with them. Nothing here imports rospy.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import shutil
import signal
import subprocess
import time
from dataclasses import dataclass

from flex_nav.exceptions import NotReadyError
from flex_nav.testing.process import StopsOnExit

IP_TIMEOUT_S = 10.0  # [s] bound of one ``ip`` command (they take milliseconds)
STOP_GRACE_S = 5.0  # [s] processes left in a namespace get SIGINT, then SIGKILL after this long
SUBNET_PREFIX = "10.231"  # private /30 subnets 10.231.X.0/30, X unique per pair in this process
_counter = itertools.count()


@dataclass(frozen=True)
class Host:
    """One side of a :class:`NetnsPair`."""

    namespace: str
    interface: str  # its end of the veth pair
    address: str  # IPv4 address of ``interface`` (a /30)

    def command(self, argv: list[str]) -> list[str]:
        """``argv`` run inside this host's namespace."""
        return ["ip", "netns", "exec", self.namespace, *argv]


def _ip(args: list[str], timeout_s: float = IP_TIMEOUT_S) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["ip", *args], capture_output=True, text=True, timeout=timeout_s, check=False)


def netns_unavailable_reason() -> str | None:
    """Why network namespaces cannot be made here (not root, no ``ip``, ``ip netns add`` refused), else None.

    The last check creates and deletes a probe namespace."""
    if os.geteuid() != 0:
        return "network namespaces need root (ip netns add)"
    if shutil.which("ip") is None:
        return "no 'ip' command (iproute2) on PATH"
    probe = f"fnprobe{os.getpid()}x{next(_counter)}"
    made = _ip(["netns", "add", probe])
    if made.returncode != 0:
        return f"'ip netns add' failed here: {made.stderr.strip() or made.returncode}"
    _ip(["netns", "del", probe])
    return None


class NetnsPair(StopsOnExit):
    """Two namespaces ``first`` and ``second`` joined by a veth pair; a context manager that always cleans up."""

    def __init__(self) -> None:
        index = next(_counter)
        tag = f"{os.getpid()}x{index}"  # veth names are at most 15 characters: fn + 7-digit pid + x + index + r
        octet = (os.getpid() * 7 + index) % 250 + 1
        self.first = Host(f"flexnav-{tag}-a", f"fn{tag}a", f"{SUBNET_PREFIX}.{octet}.1")
        self.second = Host(f"flexnav-{tag}-b", f"fn{tag}b", f"{SUBNET_PREFIX}.{octet}.2")
        self._made: list[str] = []

    @property
    def hosts(self) -> tuple[Host, Host]:
        return self.first, self.second

    def start(self) -> NetnsPair:
        """Create both namespaces, the veth pair and the addresses; on failure undo it and raise NotReadyError."""
        try:
            for host in self.hosts:
                self._run(["netns", "add", host.namespace])
                self._made.append(host.namespace)
            first, second = self.hosts
            self._run(["link", "add", first.interface, "netns", first.namespace,
                       "type", "veth", "peer", "name", second.interface, "netns", second.namespace])
            for host in self.hosts:
                self._run(["-n", host.namespace, "link", "set", "lo", "up"])
                self._run(["-n", host.namespace, "addr", "add", f"{host.address}/30", "dev", host.interface])
                self._run(["-n", host.namespace, "link", "set", host.interface, "up"])
        except BaseException:
            self.stop()
            raise
        return self

    def set_link(self, host: Host, up: bool) -> None:
        """Bring ``host``'s end of the veth pair up or down (down: its peer loses the carrier)."""
        self._run(["-n", host.namespace, "link", "set", host.interface, "up" if up else "down"])

    def sysctl(self, host: Host, name: str, value: str) -> None:
        """Set a per-namespace kernel parameter (e.g. ``net.ipv4.tcp_wmem``) in ``host``'s namespace."""
        done = subprocess.run(host.command(["sysctl", "-q", "-w", f"{name}={value}"]), capture_output=True,
                              text=True, timeout=IP_TIMEOUT_S, check=False)
        if done.returncode != 0:
            raise NotReadyError(f"sysctl {name}={value} in {host.namespace} failed: {done.stderr.strip()}")

    def pids(self, host: Host) -> list[int]:
        """The processes inside ``host``'s namespace."""
        listed = _ip(["netns", "pids", host.namespace])
        return [int(word) for word in listed.stdout.split() if word.isdigit()] if listed.returncode == 0 else []

    def stop(self) -> None:
        """End every process left in the namespaces (SIGINT, SIGKILL after STOP_GRACE_S), delete them."""
        made = [h for h in self.hosts if h.namespace in self._made]
        for sig in (signal.SIGINT, signal.SIGKILL):
            left = [pid for host in made for pid in self.pids(host)]
            for pid in left:
                with contextlib.suppress(ProcessLookupError):
                    os.kill(pid, sig)
            deadline = time.monotonic() + STOP_GRACE_S
            while left and time.monotonic() < deadline:
                time.sleep(0.05)
                left = [pid for host in made for pid in self.pids(host)]
            if not left:
                break
        for host in made:
            _ip(["netns", "del", host.namespace])
            self._made.remove(host.namespace)

    def _run(self, args: list[str]) -> None:
        done = _ip(args)
        if done.returncode != 0:
            raise NotReadyError(f"ip {' '.join(args)} failed: {done.stderr.strip() or done.returncode}")

    def __enter__(self) -> NetnsPair:
        return self.start()
