"""A state that is slow to construct: lets a test act while the behavior runner is loading."""

import time

from flex_nav.behavior.state import State


class SlowToBuild(State):
    """Sleeps in its constructor, then returns done at its first tick.

    -- build_s  float  [s] time the constructor takes
    <= done     always
    """

    def __init__(self, build_s: float) -> None:
        super().__init__(outcomes=["done"])
        time.sleep(build_s)

    def execute(self, userdata: object) -> str:
        return "done"
