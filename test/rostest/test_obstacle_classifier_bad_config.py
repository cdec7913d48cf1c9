#!/usr/bin/env python3
"""rostest node for obstacle_classifier_bad_config.test: every bad start fails loudly, naming the field."""

import sys
import tempfile
import unittest
from pathlib import Path

import rostest
from refused_start import fresh_name, run_refused

NODE = Path(__file__).resolve().parents[2] / "scripts" / "obstacle_classifier"
SHIPPED = Path(__file__).resolve().parents[2] / "models" / "obstacle_classifier.onnx"


class TestObstacleClassifierBadConfig(unittest.TestCase):
    def run_node(self, *params):
        stderr, _ = run_refused(self, NODE, fresh_name("classifier_bad"), *params)
        return stderr

    def test_missing_model_file(self):
        err = self.run_node("_model:=/nonexistent/model.onnx")
        self.assertIn("~model=/nonexistent/model.onnx", err)
        self.assertIn("'/nonexistent/model.onnx' does not exist", err)

    def test_unknown_model_type(self):
        err = self.run_node("_model_type:=ssd")
        self.assertIn("model_type 'ssd' is not valid (valid: classifier, yolo)", err)

    def test_yolo_without_model(self):
        err = self.run_node("_model_type:=yolo")
        self.assertIn("model must be set to the ONNX file when model_type is 'yolo'", err)

    def test_misspelt_parameter(self):
        err = self.run_node("_windw:=3")
        self.assertIn("windw is not a parameter of this node", err)
        self.assertIn("window", err)

    def test_bad_roi(self):
        err = self.run_node("_roi:=[0.9, 0.0, 0.1, 1.0]")
        self.assertIn("roi", err)
        self.assertIn("x_min < x_max", err)

    def test_bad_class_map(self):
        err = self.run_node("_class_map:={sofa: movable}")
        self.assertIn("class_map: class 'sofa' is not valid (valid: person, movable, clear)", err)

    def test_bad_window(self):
        err = self.run_node("_window:=0")
        self.assertIn("window", err)

    def test_broken_metadata(self):
        with tempfile.TemporaryDirectory() as tmp:
            model = Path(tmp) / "copy.onnx"
            model.write_bytes(SHIPPED.read_bytes())
            model.with_suffix(".yaml").write_text("format: flex_nav_obstacle_classifier/1\noutput: probabilities\n")
            err = self.run_node(f"_model:={model}")
        self.assertIn("field input is missing", err)
        self.assertIn("copy.yaml", err)


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "test_obstacle_classifier_bad_config", TestObstacleClassifierBadConfig, sys.argv)
