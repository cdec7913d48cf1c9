"""A headless Chromium driven by Selenium, for the console's browser tests, its benchmark and its screenshot.

Debian's ``chromium`` and ``chromium-driver`` (``tools/install.sh`` installs them) are used as installed: no
driver is downloaded. Every wait is bounded; the browser is stopped on exit (``with HeadlessBrowser() as b``).
Nothing here imports rospy.
"""

from __future__ import annotations

import shutil
import time
from pathlib import Path
from typing import Any, Callable, Optional, Sequence, TypeVar

from flex_nav.exceptions import NotReadyError
from flex_nav.testing.process import StopsOnExit

CHROMIUM = ("/usr/bin/chromium", "chromium")
CHROMEDRIVER = ("/usr/bin/chromedriver", "chromedriver")
PAGE_LOAD_TIMEOUT_S = 30.0  # [s] one page load
SCRIPT_TIMEOUT_S = 10.0  # [s] one script run in the page
POLL_S = 0.02  # [s] between two looks in wait_for
T = TypeVar("T")


def _found(candidates: tuple[str, ...]) -> Optional[str]:
    for name in candidates:
        path = shutil.which(name) if "/" not in name else (name if Path(name).is_file() else None)
        if path:
            return path
    return None


class HeadlessBrowser(StopsOnExit):
    """One headless Chromium window of ``width`` x ``height`` pixels; ``driver`` is its Selenium WebDriver."""

    def __init__(self, width: int = 1500, height: int = 1000, extra_arguments: Sequence[str] = ()) -> None:
        chromium, chromedriver = _found(CHROMIUM), _found(CHROMEDRIVER)
        if chromium is None or chromedriver is None:
            raise NotReadyError("the browser tests need Debian's chromium and chromium-driver "
                                "(tools/install.sh installs them; or: apt-get install chromium chromium-driver)")
        try:
            from selenium import webdriver  # noqa: PLC0415 - only the browser tests need it
            from selenium.webdriver.chrome.service import Service  # noqa: PLC0415
        except ImportError as err:
            raise NotReadyError(f"selenium is not installed in this Python (tools/install.sh): {err}") from err
        options = webdriver.ChromeOptions()
        options.binary_location = chromium
        for argument in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                         "--no-first-run", "--disable-extensions", f"--window-size={width},{height}",
                         *extra_arguments):
            options.add_argument(argument)
        self.driver: Any = webdriver.Chrome(options=options, service=Service(chromedriver))
        self.driver.set_page_load_timeout(PAGE_LOAD_TIMEOUT_S)
        self.driver.set_script_timeout(SCRIPT_TIMEOUT_S)

    def __enter__(self) -> HeadlessBrowser:
        return self

    def stop(self) -> None:
        self.driver.quit()

    def script(self, code: str, *args: Any) -> Any:
        """Run ``code`` (a function body; ``arguments[i]`` are ``args``) in the page and return its value."""
        return self.driver.execute_script(code, *args)

    def wait_for(self, probe: Callable[[], Optional[T]], what: str, timeout_s: float) -> T:
        """The first value of ``probe()`` that is neither None nor False, looked for every ``POLL_S`` for at most
        ``timeout_s`` [s]; NotReadyError naming ``what`` otherwise."""
        deadline = time.monotonic() + timeout_s
        while True:
            value = probe()
            if value is not None and value is not False:
                return value
            if time.monotonic() > deadline:
                raise NotReadyError(f"{what}: not within {timeout_s:g} s")
            time.sleep(POLL_S)
