"""package.xml must parse with catkin_pkg (rospack, rostopic echo and catkin refuse an invalid manifest)."""

from __future__ import annotations

from pathlib import Path

import catkin_pkg.package

REPO_ROOT = Path(__file__).resolve().parents[2]


def test_manifest_is_valid_format_3() -> None:
    package = catkin_pkg.package.parse_package(str(REPO_ROOT / "package.xml"), warnings=[])
    package.validate()
    assert package.name == "flex_nav"
    assert package.package_format == 3
    names = {d.name for d in package.build_depends}
    assert {"message_generation", "actionlib_msgs", "nav_msgs"} <= names
