#!/usr/bin/env python3
"""Write ``urdf/<profile>.urdf`` for every robot profile in ``sim/robots/`` (flex_nav_sim.urdf.robot_urdf).

``--check``: write nothing; exit 1 naming every file that is missing or differs from what the profile gives
(the unit tests run the same comparison). Exit status 0 on success.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from flex_nav_sim.profiles import available_profiles, load_profile
from flex_nav_sim.urdf import robot_urdf

URDF_DIR = Path(__file__).resolve().parent.parent / "urdf"


def stale_files(directory: Path = URDF_DIR) -> list[str]:
    """Names of the URDF files that are missing or differ from their profile's."""
    return [f"{name}.urdf" for name in available_profiles()
            if not (directory / f"{name}.urdf").is_file()
            or (directory / f"{name}.urdf").read_text() != robot_urdf(load_profile(name))]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare only; exit 1 if a file is stale")
    args = parser.parse_args(argv)
    stale = stale_files()
    if args.check:
        if stale:
            print(f"gen_urdf: stale or missing in {URDF_DIR}: {', '.join(stale)} (run tools/gen_urdf.py)")
            return 1
        return 0
    URDF_DIR.mkdir(exist_ok=True)
    for name in available_profiles():
        (URDF_DIR / f"{name}.urdf").write_text(robot_urdf(load_profile(name)))
    print(f"gen_urdf: wrote {len(available_profiles())} files into {URDF_DIR}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
