"""flexbe_testing: FlexBE's state and behavior tester (the Tester with its YAML test cases), on flex_nav's compat
``flexbe_core``.

A test case is FlexBE's YAML (one case per file, named by the file)::

    path: example_flexbe_states.calculation_state   # module of the state (or of the behavior: with ``name``)
    class: CalculationState
    params:                                        # constructor arguments ("lambda ..." strings are evaluated)
      calculation: "lambda x: x * 2"
    input:                                         # userdata given to the state
      input_value: 21
    output:                                        # userdata expected afterwards
      output_value: 42
    outcome: done                                  # expected outcome
    # import_only: true                            # only check that the class imports

``Tester().run_test(name, config)`` imports the class, instantiates it with ``params``, executes it directly
(``on_start``, ``execute`` + ``sleep`` until an outcome, ``on_stop``; a behavior: ``prepare_for_execution``,
``confirm`` and its state machine stepped the same way) and compares outcome and outputs; it returns 1 on success,
0 otherwise, and records unittest-style checks (``test_<name>_pass``, ``_outcome``, ``_output_<key>``) that
``perform_rostest`` / :meth:`Tester.test_case_class` turn into a unittest TestCase. Unlike FlexBE's, every run is
bounded (``time_limit`` [s] per case, default 30) and nothing but ``lambda`` strings is evaluated. Not supported:
``launch`` (a roslaunch context) and ``data`` (a bag file as data source) report the case as failed with the reason.
"""

from flex_nav.compat.flexbe_testing.data_provider import DataProvider
from flex_nav.compat.flexbe_testing.logger import Logger
from flex_nav.compat.flexbe_testing.test_context import TestContext
from flex_nav.compat.flexbe_testing.test_interface import TestInterface
from flex_nav.compat.flexbe_testing.tester import Tester, load_test_cases

__all__ = ["DataProvider", "Logger", "TestContext", "TestInterface", "Tester", "load_test_cases"]
