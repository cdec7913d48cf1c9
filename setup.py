"""Python packaging for flex_nav: used by pip (tools/install.sh) and by catkin_python_setup().

Three import packages live in ``src/``: ``flex_nav`` (engine, ROS adapters, navigation,
perception), ``flex_nav_states`` (a link to the top-level ``states/``) and ``flex_nav_sim``
(a link to the top-level ``sim/``).
"""

from pathlib import Path

from setuptools import find_packages, setup

HERE = Path(__file__).resolve().parent


def share_files(*folders: str) -> list:
    """(install dir, files) pairs: each folder's files under share/flex_nav/<folder>, found there at run time by
    flex_nav.resources (catkin's install rules in CMakeLists.txt put the same folders in the same place)."""
    pairs = []
    for folder in folders:
        for directory in sorted(p for p in [HERE / folder, *(HERE / folder).rglob("*")] if p.is_dir()):
            files = sorted(str(f.relative_to(HERE)) for f in directory.iterdir() if f.is_file())
            if files:
                pairs.append((str(Path("share/flex_nav") / directory.relative_to(HERE)), files))
    return pairs


setup(
    name="flex_nav",
    version="0.1.0",
    description="Flexible Navigation for ROS 1 with FlexBE-style behaviors and a pybullet simulator",
    license="BSD-3-Clause",
    python_requires=">=3.8",
    package_dir={"": "src"},
    packages=find_packages("src"),
    package_data={
        "flex_nav": ["py.typed", "console/web/*"],  # the operator console's page (flex_nav.console.server)
        "flex_nav_states": ["py.typed"],
        "flex_nav_sim": ["py.typed", "worlds/*.yaml", "worlds/maps/*", "robots/*", "models/*"],
    },
    data_files=share_files("behaviors", "models", "config", "launch", "urdf", "rviz"),
)
