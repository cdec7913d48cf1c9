"""Runs behaviors on ROS: loads one by name or file, executes it in its own thread, supervises it over topics.

``rosrun flex_nav behavior_runner _behavior:=NAME_OR_PATH _autonomy:=LEVEL`` starts one at once; without
``~behavior`` the runner waits for a ``start`` command. Parameters (private):

- ``~behavior`` (str, ""): behavior name (looked up in ``~behavior_path``), YAML file, or a FlexBE behavior class
  as ``py:package.module:ClassName`` (built with :func:`flex_nav.compat.flexbe_core.build_behavior`; only from
  this parameter, never from a remote ``start`` command)
- ``~autonomy`` (str/int, "full"): initial autonomy level (off, low, high, full or 0..3)
- ``~supervised`` (bool, true): enforce autonomy levels (false: every transition fires by itself)
- ``~parameters`` (dict, {}): behavior parameter overrides, e.g. ``{backup_distance: 0.1}``
- ``~inputs`` (dict, {}): values for the behavior's input keys
- ``~behavior_path`` (list of dirs, [<package>/behaviors]): where behavior names are looked up
- ``~exit_when_done`` (bool, false): shut the node down when the behavior ends (exit 0 only if it FINISHED)
- ``~robot_profile`` (str, ""): the robot's profile (kobuki, create2, turtlebot4; flex_nav_robot.launch sets it);
  every YAML behavior started here that declares a ``profile`` parameter gets it, unless the start sets one

Commands arrive on ``~command`` (BehaviorCommand); every command is answered on ``~command_feedback``.
What the behavior does is published by :class:`~flex_nav.ros.operator_interface.OperatorPublisher`.
Each run gets its own :class:`~flex_nav.ros.proxies.RosProxies`, shut down (goals cancelled, topics
unregistered) when it ends, so runs never share connections. Command arguments are plain strings;
``KEY=VALUE`` values are parsed with ``yaml.safe_load`` (never eval'd). The runner installs flex_nav's
``smach`` / ``flexbe_core`` aliases (unless the real packages exist), so state libraries written for them load.
"""

from __future__ import annotations

import concurrent.futures
import importlib
import threading
from pathlib import Path
from typing import Any, Callable, Dict, FrozenSet, List, Optional, Sequence, Tuple

import rospy
import yaml

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.behavior import Behavior
from flex_nav.behavior.context import BehaviorContext
from flex_nav.behavior.executor import BehaviorExecutor, BehaviorResult
from flex_nav.compat import install_aliases
from flex_nav.compat.flexbe_core.behavior import Behavior as FlexBEBehavior
from flex_nav.compat.flexbe_core.behavior import build_behavior
from flex_nav.exceptions import BehaviorError, ConfigError, FlexNavError, choices_message
from flex_nav.msg import BehaviorCommand
from flex_nav.ros.operator_interface import OperatorPublisher
from flex_nav.ros.proxies import RosProxies
from flex_nav.ros.ros_clock import RosClock

PACKAGE_BEHAVIORS = Path(__file__).resolve().parents[3] / "behaviors"
PYTHON_PREFIX = "py:"  # ~behavior given as a FlexBE behavior class: py:package.module:ClassName
COMMAND_APPLY_TIMEOUT_S = 2.0  # [s] bound on waiting for the executor to apply a command
STOP_TIMEOUT_S = 5.0  # [s] bound on waiting for a preempted behavior to exit its states

Loader = Callable[[str, Dict[str, Any], Sequence[Path]], Behavior]


def load_behavior_file(name_or_path: str, parameters: Dict[str, Any], search_path: Sequence[Path]) -> Behavior:
    """The default loader: the YAML behavior loader of :mod:`flex_nav.behavior.yaml_loader`."""
    from flex_nav.behavior.yaml_loader import load_behavior  # noqa: PLC0415 - keeps the node's import light

    return load_behavior(name_or_path, parameters=parameters, search_path=list(search_path))


def with_robot_profile(parameters: Dict[str, Any], declared: FrozenSet[str], robot_profile: str) -> Dict[str, Any]:
    """``parameters`` plus ``profile: robot_profile`` when the behavior declares ``profile``, a robot profile is
    known and the parameters do not set one (an explicit override wins)."""
    if not robot_profile or "profile" in parameters or "profile" not in declared:
        return dict(parameters)
    return {**parameters, "profile": robot_profile}


def flexbe_behavior_class(spec: str) -> type:
    """The FlexBE behavior class named ``package.module:ClassName``; ConfigError saying what is wrong."""
    module_name, sep, class_name = spec.partition(":")
    if not sep or not module_name or not class_name:
        raise ConfigError(f"FlexBE behavior {spec!r} must be given as package.module:ClassName")
    install_aliases()
    try:
        module = importlib.import_module(module_name)
    except ImportError as err:
        raise ConfigError(f"FlexBE behavior {spec!r}: cannot import {module_name}: {err}") from err
    found = getattr(module, class_name, None)
    if not (isinstance(found, type) and issubclass(found, FlexBEBehavior)):
        classes = [n for n, v in vars(module).items() if isinstance(v, type) and issubclass(v, FlexBEBehavior)]
        raise ConfigError(choices_message(f"FlexBE behavior class in {module_name}", class_name, classes))
    return found


def parse_assignments(items: Sequence[str]) -> Dict[str, Any]:
    """``["a=1", "b=[1, 2]"]`` -> ``{"a": 1, "b": [1, 2]}`` (values by yaml.safe_load)."""
    result: Dict[str, Any] = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key:
            raise ConfigError(f"argument {item!r} is not KEY=VALUE")
        try:
            result[key] = yaml.safe_load(text) if text else ""
        except yaml.YAMLError as err:
            raise ConfigError(f"argument {item!r}: value is not valid YAML ({err})") from err
    return result


class BehaviorRunner:
    """One runner node: at most one behavior runs at a time; commands start, stop and supervise it."""

    COMMANDS = ("start", "stop", "autonomy", "approve", "force", "pause", "resume", "preempt", "lock", "unlock")

    def __init__(self, search_path: Sequence[Path], supervised: bool = True, loader: Loader = load_behavior_file,
                 on_done: Optional[Callable[[BehaviorResult], None]] = None, robot_profile: str = "") -> None:
        self.search_path = list(search_path)
        self.robot_profile = robot_profile
        self.supervised = supervised
        self.loader = loader
        self.on_done = on_done
        install_aliases()  # smach / flexbe_core state libraries in YAML behaviors import flex_nav's
        self.operator = OperatorPublisher()
        self._lock = threading.Lock()
        self._executor: Optional[BehaviorExecutor] = None
        self._thread: Optional[threading.Thread] = None
        self._name = ""
        self._command_sub = rospy.Subscriber("~command", BehaviorCommand, self._on_command, queue_size=10)
        self.operator.publish_idle("", "no behavior started", int(Autonomy.FULL))

    # --- lifecycle -----------------------------------------------------------------------------------
    def start(self, name_or_path: str, autonomy: object = Autonomy.FULL, parameters: Optional[Dict[str, Any]] = None,
              inputs: Optional[Dict[str, Any]] = None) -> str:
        """Load, validate and start a behavior in its own thread; ConfigError/BehaviorError if it cannot."""
        level = Autonomy.parse(autonomy)
        with self._lock:
            if self._thread is not None and self._thread.is_alive():
                raise ConfigError(f"behavior {self._name!r} is still running; stop it first")
            proxies = RosProxies()
            context = BehaviorContext(name_or_path, autonomy=level, supervised=self.supervised, clock=RosClock(),
                                      proxies=proxies)
            try:
                if name_or_path.startswith(PYTHON_PREFIX):
                    behavior = build_behavior(flexbe_behavior_class(name_or_path[len(PYTHON_PREFIX):]),
                                              parameters=dict(parameters or {}), context=context)
                else:
                    behavior = self.loader(name_or_path, self._yaml_parameters(name_or_path, parameters or {}),
                                           self.search_path)
                context.name = behavior.name
                executor = BehaviorExecutor(
                    behavior, inputs=dict(inputs or {}), context=context, should_stop=rospy.is_shutdown
                )
            except BaseException:
                proxies.shutdown()  # connections a state made while being built must not outlive a failed start
                raise
            self.operator.attach(executor.context.hooks, behavior.name, int(level))
            self._executor, self._name = executor, behavior.name
            self._thread = threading.Thread(
                target=self._run, args=(executor, proxies), name=f"behavior {behavior.name}", daemon=True
            )
            self._thread.start()
        return f"started behavior {behavior.name!r} at autonomy {level.name}"

    def _yaml_parameters(self, name_or_path: str, parameters: Dict[str, Any]) -> Dict[str, Any]:
        if not self.robot_profile:
            return dict(parameters)
        from flex_nav.behavior.yaml_loader import declared_parameter_names  # noqa: PLC0415 - as the loader

        merged = with_robot_profile(parameters, declared_parameter_names(name_or_path, self.search_path),
                                    self.robot_profile)
        if merged != parameters:
            rospy.loginfo(f"behavior {name_or_path!r}: profile {self.robot_profile!r} (the robot's, ~robot_profile)")
        return merged

    def _run(self, executor: BehaviorExecutor, proxies: RosProxies) -> None:
        try:
            result = executor.run()
        finally:
            proxies.shutdown()
        rospy.loginfo(f"behavior {self._name!r} ended: {result.status.name} {result.outcome or ''} {result.reason}")
        if self.on_done is not None:
            self.on_done(result)

    def stop(self, timeout_s: float = STOP_TIMEOUT_S) -> str:
        """Preempt the running behavior and wait (bounded) until it exited its states."""
        with self._lock:
            executor, thread = self._executor, self._thread
        if executor is None or thread is None or not thread.is_alive():
            return "no behavior is running"
        executor.preempt("stopped by the operator")
        thread.join(timeout_s)
        if thread.is_alive():
            raise BehaviorError(f"behavior {self._name!r} did not stop within {timeout_s:.1f} s")
        return f"stopped behavior {self._name!r}"

    def result(self) -> Optional[BehaviorResult]:
        with self._lock:
            executor = self._executor
        return executor.result() if executor is not None and executor.status.is_terminal else None

    def shutdown(self) -> None:
        try:
            self.stop()
        except BehaviorError as err:
            rospy.logerr(str(err))
        self.operator.close()

    # --- commands ------------------------------------------------------------------------------------
    def _on_command(self, msg: BehaviorCommand) -> None:
        args = list(msg.args)
        try:
            message = self.handle(msg.command, args)
            ok = True
        except (FlexNavError, concurrent.futures.TimeoutError) as err:
            ok, message = False, str(err) or type(err).__name__
        (rospy.loginfo if ok else rospy.logwarn)(f"command {msg.command} {' '.join(args)}: {message}")
        self.operator.publish_feedback(msg.command, args, ok, message)

    def handle(self, command: str, args: List[str]) -> str:
        """Apply one operator command; returns what was done, raises FlexNavError saying why not."""
        if command not in self.COMMANDS:
            raise ConfigError(choices_message("command", command, self.COMMANDS))
        if command == "start":
            if not args:
                raise ConfigError("start needs a behavior name or file")
            if "/" in args[0] or args[0].endswith((".yaml", ".yml")) or args[0].startswith(PYTHON_PREFIX):
                raise ConfigError(
                    f"start takes a behavior name from the search path, not a file: {args[0]!r} "
                    f"(search path: {', '.join(str(p) for p in self.search_path)})"
                )
            options = parse_assignments(args[1:])
            autonomy = options.pop("autonomy", Autonomy.FULL)
            return self.start(args[0], autonomy, options)
        if command == "stop":
            return self.stop()
        executor = self._executor
        if executor is None or executor.status.is_terminal:
            raise ConfigError(f"{command}: no behavior is running")
        future, expected = self._dispatch(executor, command, args)
        applied = future.result(timeout=COMMAND_APPLY_TIMEOUT_S)
        if command == "autonomy":
            self.operator.publish_autonomy(int(executor.autonomy))
        return applied or expected

    def _dispatch(self, executor: BehaviorExecutor, command: str, args: List[str]
                  ) -> Tuple[concurrent.futures.Future[str], str]:
        # command: (min args, max args, apply, what it did)
        table: Dict[str, Tuple[int, int, Callable[[], concurrent.futures.Future[str]], str]] = {
            "autonomy": (1, 1, lambda: executor.set_autonomy(args[0]), f"autonomy set to {args[:1]}"),
            "approve": (1, 2, lambda: executor.approve(args[0], args[1] if len(args) > 1 else None),
                        f"approved {args[:2]}"),
            "force": (2, 2, lambda: executor.force_transition(args[0], args[1]), f"forced {args[:2]}"),
            "pause": (0, 0, executor.pause, "paused"),
            "resume": (0, 0, executor.resume, "resumed"),
            "preempt": (0, 0, lambda: executor.preempt("preempted by the operator"), "preempt requested"),
            "lock": (1, 1, lambda: executor.lock(args[0]), f"locked {args[:1]}"),
            "unlock": (1, 1, lambda: executor.unlock(args[0]), f"unlocked {args[:1]}"),
        }
        low, high, apply, what = table[command]
        if not low <= len(args) <= high:
            raise ConfigError(f"{command} takes {low}..{high} argument(s), got {len(args)}: {args}")
        return apply(), what
