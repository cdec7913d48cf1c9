"""Python packaging for flex_nav: used by pip (tools/install.sh) and by catkin_python_setup().

Three import packages live in ``src/``: ``flex_nav`` (engine, ROS adapters, navigation,
perception), ``flex_nav_states`` (a link to the top-level ``states/``) and ``flex_nav_sim``
(a link to the top-level ``sim/``).
"""

from setuptools import find_packages, setup

setup(
    name="flex_nav",
    version="0.1.0",
    description="Flexible Navigation for ROS 1 with FlexBE-style behaviors and a pybullet simulator",
    license="BSD-3-Clause",
    python_requires=">=3.8",
    package_dir={"": "src"},
    packages=find_packages("src"),
    package_data={
        "flex_nav": ["py.typed"],
        "flex_nav_states": ["py.typed"],
        "flex_nav_sim": ["py.typed", "worlds/*.yaml", "worlds/maps/*", "robots/*", "models/*"],
    },
)
