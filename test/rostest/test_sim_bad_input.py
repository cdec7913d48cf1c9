#!/usr/bin/env python3
"""rostest node for sim_bad_input.test: each bad start of the sim node fails loudly and cleanly."""

import os
import sys
import tempfile
import unittest
from pathlib import Path

import rostest
from refused_start import fresh_name, run_refused

from flex_nav_sim.world import available_worlds

SIM = Path(__file__).resolve().parents[2] / "scripts" / "sim"


class TestSimBadInput(unittest.TestCase):
    def run_sim(self, *params):
        stderr, publishers = run_refused(self, SIM, fresh_name("sim_bad"), *params)
        self.assertNotIn("/clock", [topic for topic, _ in publishers])
        return stderr

    def test_unknown_world(self):
        err = self.run_sim("_world:=moon")
        shipped = ", ".join(available_worlds())
        self.assertTrue({"corridor", "lab", "open_room", "two_rooms"} <= set(available_worlds()))
        self.assertIn(f"world 'moon' is not valid (valid: {shipped})", err)

    def test_unknown_profile(self):
        err = self.run_sim("_world:=lab", "_robots:=robot1:roomba")
        self.assertIn("robot profile 'roomba' is not valid (valid: create2, kobuki, turtlebot4)", err)

    def test_malformed_world_file(self):
        with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as bad:
            bad.write("name: broken\nrooms: [{min: [0, 0]\n")
        try:
            err = self.run_sim(f"_world:={bad.name}")
        finally:
            os.unlink(bad.name)
        self.assertIn("malformed YAML", err)
        self.assertIn(bad.name, err)

    def test_robot_spawned_inside_obstacle(self):
        err = self.run_sim("_world:=lab", "_robots:=robot1:kobuki:4.0:3.0:0")
        self.assertIn("robot 'robot1' spawned at (4.00, 3.00) overlaps obstacle 'island'", err)

    def test_two_robots_one_namespace(self):
        err = self.run_sim("_world:=lab", "_robots:=robot1:kobuki:1:1 robot1:create2:1:5")
        self.assertIn("two robots share the namespace 'robot1'", err)

    def test_bad_parameter(self):
        err = self.run_sim("_world:=lab", "_rtf:=-1")
        self.assertIn("rtf = -1 is outside [0.0, 1000.0]", err)


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "sim_bad_input", TestSimBadInput, sys.argv)
