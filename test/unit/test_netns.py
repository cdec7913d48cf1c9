"""flex_nav.testing.netns: two network namespaces joined by a veth pair (the two-host system test's machines).

The names and the reasons to skip need nothing; the pair itself needs root and ``ip`` (skipped otherwise)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from flex_nav.testing import netns
from flex_nav.testing.netns import NetnsPair, netns_unavailable_reason

SERVER = ("import socket, sys; s = socket.socket(); s.bind((sys.argv[1], 5555)); s.listen()\n"
          "while True: s.accept()[0].close()")
CLIENT = ("import socket, sys; s = socket.socket(); s.settimeout(1.0)\n"
          "try: s.connect((sys.argv[1], 5555)); print('connected')\n"
          "except OSError as err: print('refused', err)")


def test_names_fit_interface_limits_and_differ_between_pairs() -> None:
    one, two = NetnsPair(), NetnsPair()  # nothing is created before start()
    for host in (*one.hosts, *two.hosts):
        assert len(host.interface) <= 15  # IFNAMSIZ - 1
    assert len({h.namespace for h in (*one.hosts, *two.hosts)}) == 4
    assert len({h.interface for h in (*one.hosts, *two.hosts)}) == 4
    assert one.first.address.rsplit(".", 1)[0] == one.second.address.rsplit(".", 1)[0]  # one /30
    assert (one.first.address.endswith(".1"), one.second.address.endswith(".2")) == (True, True)


def test_reasons_to_skip(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(netns.os, "geteuid", lambda: 1000)
    assert "root" in (netns_unavailable_reason() or "")
    monkeypatch.setattr(netns.os, "geteuid", lambda: 0)
    monkeypatch.setattr(netns.shutil, "which", lambda _name: None)
    assert "'ip'" in (netns_unavailable_reason() or "")


def _connect(host: netns.Host, address: str) -> str:
    done = subprocess.run(host.command([sys.executable, "-c", CLIENT, address]), capture_output=True, text=True,
                          timeout=20, check=False)
    return done.stdout.strip()


def test_the_pair_links_two_namespaces_and_leaves_nothing_behind() -> None:
    reason = netns_unavailable_reason()
    if reason is not None:
        pytest.skip(reason)
    pair = NetnsPair().start()
    try:
        server = subprocess.Popen(pair.second.command([sys.executable, "-c", SERVER, pair.second.address]))
        for _ in range(100):  # the server binds within a second
            if _connect(pair.first, pair.second.address) == "connected":
                break
        assert _connect(pair.first, pair.second.address) == "connected"
        assert pair.pids(pair.second) == [server.pid]  # ip netns exec runs the command itself
        pair.set_link(pair.first, up=False)
        assert _connect(pair.first, pair.second.address).startswith("refused")
        pair.set_link(pair.first, up=True)
        assert _connect(pair.first, pair.second.address) == "connected"
    finally:
        pair.stop()  # the server is still running inside: stop() ends it
    assert server.wait(timeout=10) is not None
    listed = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True, timeout=10, check=True).stdout
    assert pair.first.namespace not in listed and pair.second.namespace not in listed
