"""Where flex_nav's data files are: ``behaviors/``, ``models/``, ``config/``, ``launch/``.

In a source checkout (and an editable or catkin devel install) they are the repository's own folders, beside
``package.xml``. An installed package finds them under ``<prefix>/share/flex_nav/``, where ``setup.py``
(``data_files``) and catkin's install rules (``CMakeLists.txt``) put them. ``FLEX_NAV_SHARE`` overrides both.
No module computes these paths from its own depth in the package.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import List

from flex_nav.exceptions import ConfigError

SHARE_ENV = "FLEX_NAV_SHARE"
PACKAGE_NAME = "flex_nav"
_HERE = Path(__file__).resolve()


def _candidates() -> List[Path]:
    found: List[Path] = []
    override = os.environ.get(SHARE_ENV, "")
    if override:
        found.append(Path(override))
    source_root = _HERE.parents[2]  # <repo>/src/flex_nav/resources.py -> <repo>
    if (source_root / "package.xml").is_file():
        found.append(source_root)
    for parent in _HERE.parents:  # <prefix>/lib/python3.X/site-packages/flex_nav -> <prefix>/share/flex_nav
        found.append(parent / "share" / PACKAGE_NAME)
    return found


def share_dir() -> Path:
    """The directory holding ``behaviors/`` (ConfigError naming where it looked when there is none)."""
    candidates = _candidates()
    for candidate in candidates:
        if (candidate / "behaviors").is_dir():
            return candidate
    raise ConfigError(f"flex_nav's data files (behaviors/) are not installed; looked in "
                      f"{', '.join(str(c) for c in candidates[:4])}, ... (set {SHARE_ENV} to the folder holding them)")


def behaviors_dir() -> Path:
    return share_dir() / "behaviors"


def models_dir() -> Path:
    return share_dir() / "models"
