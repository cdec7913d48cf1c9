"""``python -m flex_nav.apps.console_screenshot URL OUT.png``: a picture of the operator console as a browser shows
it (headless Chromium through Selenium, :mod:`flex_nav.testing.browser`).

Opens ``URL`` (``http://127.0.0.1:PORT/``; with a token, ``http://HOST:PORT/?token=...``), waits until the behavior's
graph and the map are drawn (at most ``--timeout`` seconds), waits ``--settle`` seconds more for live overlays, and
writes the window's PNG. Exit status 0, or 2 with the reason (no browser, nothing drawn in time).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Optional, Sequence

from flex_nav.exceptions import FlexNavError
from flex_nav.testing.browser import HeadlessBrowser

READY_SCRIPT = ("return document.querySelectorAll('#graph svg g.node').length > 0 && "
                "document.getElementById('map-info').textContent.startsWith('map ');")


def screenshot(url: str, out: Path, *, width: int, height: int, timeout_s: float, settle_s: float) -> Path:
    """Write the console at ``url`` to ``out`` (PNG) once its graph and map are drawn; NotReadyError if not in time."""
    with HeadlessBrowser(width, height) as browser:
        browser.driver.get(url)
        browser.wait_for(lambda: bool(browser.script(READY_SCRIPT)), "the console's graph and map drawn", timeout_s)
        time.sleep(settle_s)
        out.parent.mkdir(parents=True, exist_ok=True)
        browser.driver.save_screenshot(str(out))
    return out


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m flex_nav.apps.console_screenshot", description=__doc__)
    parser.add_argument("url")
    parser.add_argument("out", type=Path)
    parser.add_argument("--width", type=int, default=1600, help="[px] window width (default %(default)s)")
    parser.add_argument("--height", type=int, default=1000, help="[px] window height (default %(default)s)")
    parser.add_argument("--timeout", type=float, default=60.0, help="[s] wait for the drawing (default %(default)s)")
    parser.add_argument("--settle", type=float, default=1.0, help="[s] then wait this long (default %(default)s)")
    args = parser.parse_args(argv)
    try:
        path = screenshot(args.url, args.out, width=args.width, height=args.height, timeout_s=args.timeout,
                          settle_s=args.settle)
    except FlexNavError as err:
        print(f"console_screenshot: {err}", file=sys.stderr)
        return 2
    print(f"console_screenshot: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
