"""Runs behaviors on ROS: loads one by name or file, executes it in its own thread, supervises it over topics.

``rosrun flex_nav behavior_runner _behavior:=NAME_OR_PATH _autonomy:=LEVEL`` starts one at once; without
``~behavior`` the runner waits for a ``start`` command. Parameters (private):

- ``~behavior`` (str, ""): behavior name (looked up in ``~behavior_path``), YAML file (a path with a ``/`` or a
  ``.yaml`` suffix), or a FlexBE behavior class as ``py:package.module:ClassName`` (built with
  :func:`flex_nav.compat.flexbe_core.build_behavior`). Trusted: it comes from whoever launches the node. A load
  that fails here (including a bad file: not UTF-8, over a limit) ends the node with a logfatal and exit 2.
- ``~autonomy`` (str/int, "full"): initial autonomy level (off, low, high, full or 0..3)
- ``~supervised`` (bool, true): enforce autonomy levels (false: every transition fires by itself)
- ``~parameters`` (dict, {}): behavior parameter overrides, e.g. ``{backup_distance: 0.1}``
- ``~inputs`` (dict, {}): values for the behavior's input keys
- ``~behavior_path`` (list of dirs, [<package>/behaviors]): where behavior names are looked up
- ``~exit_when_done`` (bool, false): shut the node down when the behavior ends (exit 0 only if it FINISHED)
- ``~robot_profile`` (str, ""): the robot's profile (kobuki, create2, turtlebot4; flex_nav_robot.launch sets it);
  every YAML behavior started here that declares a ``profile`` parameter gets it, unless the start sets one

Commands arrive on ``~command`` (BehaviorCommand); every command is answered on ``~command_feedback``.
What the behavior does is published by :class:`~flex_nav.ros.operator_interface.OperatorPublisher`, and
what it is on the latched ``~structure`` (JSON, :mod:`flex_nav.behavior.structure`; no behavior: no states), and
the active states' userdata on the latched ``~userdata`` (JSON, :mod:`flex_nav.behavior.userdata_summary`: each
value summarized and bounded, at most ``userdata_rate_hz`` messages a second, only when it changed;
:mod:`flex_nav.ros.userdata_publisher`).
Each run gets its own :class:`~flex_nav.ros.proxies.RosProxies`, shut down (goals cancelled, topics
unregistered) when it ends, so runs of flex_nav's states never share connections (states written for FlexBE use
the ``flexbe_core`` layer's process-wide proxies, as in FlexBE). The runner installs flex_nav's
``smach`` / ``flexbe_core`` aliases (unless the real packages exist), so state libraries written for them load.

Commands come from any node on the ROS graph (ROS 1 has no authentication), so they are not trusted:

- ``start NAME [autonomy=LEVEL] [KEY=VALUE ...]`` takes only a behavior *name* found on ``~behavior_path``
  (:meth:`~flex_nav.behavior.yaml_loader.BehaviorSource.remote`): never a path, a file of the working
  directory or a ``py:`` class. Refusals name the behavior and the problem in its file on the search path;
  an unknown name is answered with the valid names. ``KEY=VALUE`` values are parsed with a bounded
  ``yaml.safe_load`` (:func:`~flex_nav.behavior.yaml_limits.safe_load_bounded`), never evaluated.
- Every load is bounded (:class:`~flex_nav.behavior.yaml_limits.LoadLimits`: 1 MiB of files, 50 000 YAML nodes
  with aliases expanded, 1 000 aliases, 64 levels, 1 000 states, 16 nested sub-behaviors) and runs off the
  command callback in a worker thread: ``start`` is answered at once with ``pending`` true ("loading NAME"),
  then, when the load ends, with the final answer (started, or refused with the reason). A load that takes
  longer than ``LOAD_TIMEOUT_S`` (10 s) is answered as failed; its worker may finish later in a daemon thread,
  but its result is discarded and never started. A second ``start`` while one loads is refused; ``stop``
  cancels a load in progress.
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import importlib
import threading
import time
from pathlib import Path
from typing import Any, Callable, Dict, FrozenSet, List, Optional, Sequence, Tuple, Union

import rospy

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.background_load import BackgroundLoad
from flex_nav.behavior.behavior import Behavior
from flex_nav.behavior.context import BehaviorContext
from flex_nav.behavior.executor import BehaviorExecutor, BehaviorResult
from flex_nav.behavior.structure import structure_json
from flex_nav.behavior.yaml_limits import DEFAULT_LIMITS, safe_load_bounded
from flex_nav.behavior.yaml_loader import BehaviorSource, declared_parameter_names, list_behaviors, load_behavior
from flex_nav.compat import install_aliases
from flex_nav.compat.flexbe_core.behavior import Behavior as FlexBEBehavior
from flex_nav.compat.flexbe_core.behavior import build_behavior
from flex_nav.exceptions import BehaviorError, BehaviorLoadError, ConfigError, FlexNavError, choices_message
from flex_nav.msg import BehaviorCommand
from flex_nav.resources import behaviors_dir
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.operator_interface import OperatorPublisher
from flex_nav.ros.proxies import RosProxies
from flex_nav.ros.ros_clock import RosClock, next_grid_point
from flex_nav.ros.userdata_publisher import DEFAULT_RATE_HZ, UserdataPublisher, no_userdata, userdata_topic

PACKAGE_BEHAVIORS = behaviors_dir()
PYTHON_PREFIX = "py:"  # ~behavior given as a FlexBE behavior class: py:package.module:ClassName
COMMAND_APPLY_TIMEOUT_S = 2.0  # [s] bound on waiting for the executor to apply a command
STOP_TIMEOUT_S = 5.0  # [s] bound on waiting for a preempted behavior to exit its states
LOAD_TIMEOUT_S = 10.0  # [s] bound on a load (read, build, validate); = the loader's own max_load_s
LOCKSTEP_START_GRID_S = 1.0  # [s] lockstep: a behavior starts at a whole second of simulated time
LOCKSTEP_START_WAIT_S = 10.0  # [s] wall: bound on waiting for that second (a stalled clock starts it anyway)
LOCKSTEP_START_TOLERANCE_S = 0.005  # [s] the simulation held at the start second stands this close after it
SHOWN_CHARS = 60  # characters of a remote argument repeated in an answer

Loader = Callable[[BehaviorSource, Dict[str, Any], Sequence[Path]], Behavior]
Answer = Callable[[bool, str, bool], None]  # (ok, message, pending): an answer to a command


def load_behavior_file(source: BehaviorSource, parameters: Dict[str, Any], search_path: Sequence[Path]) -> Behavior:
    """The default loader: the bounded YAML behavior loader of :mod:`flex_nav.behavior.yaml_loader`."""
    return load_behavior(source, parameters=parameters, search_path=list(search_path))


def with_robot_profile(parameters: Dict[str, Any], declared: FrozenSet[str], robot_profile: str) -> Dict[str, Any]:
    """``parameters`` plus ``profile: robot_profile`` when the behavior declares ``profile``, a robot profile is
    known and the parameters do not set one (an explicit override wins)."""
    if not robot_profile or "profile" in parameters or "profile" not in declared:
        return dict(parameters)
    return {**parameters, "profile": robot_profile}


def wait_for_start_grid(clock: Any, name: str, wait_s: float = LOCKSTEP_START_WAIT_S) -> float:
    """Lockstep: behavior ``name`` starts on the grid of whole seconds of simulated time (held there by ``clock``, a
    RosClock with a lockstep participant), so its states tick at the same simulated times whenever its node came up
    (each state's ticks follow from its entry). A grid point the simulation passed before the hold took (no /clock
    yet: ROS time jumped from 0 to 1.16 s over the point 1 s, and the behavior started off the grid) does not count:
    the next one is waited for. Bounded by ``wait_s`` [s] of wall time (a stalled clock starts it anyway, with a
    warning). Returns the ROS time [s] it starts at."""
    never = threading.Event()
    wall_deadline = time.monotonic() + wait_s
    start_s = next_grid_point(float(clock.now()), LOCKSTEP_START_GRID_S)
    now_s = start_s
    while not rospy.is_shutdown():
        now_s = float(clock.now())
        if now_s >= start_s:
            if now_s <= start_s + LOCKSTEP_START_TOLERANCE_S:
                return now_s
            start_s = next_grid_point(now_s, LOCKSTEP_START_GRID_S)  # passed before the hold took
        if time.monotonic() > wall_deadline:
            rospy.logwarn(f"behavior {name!r}: simulated time did not stand at {start_s:.3f} s within {wait_s:g} s "
                          f"of wall time: started at {now_s:.3f} s")
            return now_s
        clock.wait_until(start_s, never)
    return now_s


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


def _shown(text: str) -> str:
    """``text`` for an answer: repr, cut to SHOWN_CHARS characters."""
    return repr(text) if len(text) <= SHOWN_CHARS else f"{text[:SHOWN_CHARS]!r}... ({len(text)} characters)"


def parse_assignments(items: Sequence[str]) -> Dict[str, Any]:
    """``["a=1", "b=[1, 2]"]`` -> ``{"a": 1, "b": [1, 2]}`` (values by a bounded yaml.safe_load: all the values
    together within DEFAULT_LIMITS' max_bytes, each within its alias, node and nesting limits)."""
    result: Dict[str, Any] = {}
    total = sum(len(item) for item in items)
    if total > DEFAULT_LIMITS.max_bytes:
        raise ConfigError(f"the arguments are {total} characters long (limit max_bytes={DEFAULT_LIMITS.max_bytes})")
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key:
            raise ConfigError(f"argument {_shown(item)} is not KEY=VALUE")
        try:
            result[key] = safe_load_bounded(text, f"argument {key}") if text else ""
        except BehaviorLoadError as err:
            raise ConfigError(f"argument {_shown(item)}: value is not valid YAML within the limits ({err.reason})"
                              ) from err
    return result


@dataclasses.dataclass(frozen=True)
class _Built:
    """A loaded behavior, ready to run (made by a load's worker thread)."""

    behavior: Behavior
    executor: BehaviorExecutor
    proxies: RosProxies
    level: Autonomy
    structure: str  # JSON for ~structure (flex_nav.behavior.structure)


class BehaviorRunner:
    """One runner node: at most one behavior loads or runs at a time; commands start, stop and supervise it."""

    COMMANDS = ("start", "stop", "autonomy", "approve", "force", "pause", "resume", "preempt", "lock", "unlock")

    def __init__(self, search_path: Sequence[Path], supervised: bool = True, loader: Loader = load_behavior_file,
                 on_done: Optional[Callable[[BehaviorResult], None]] = None, robot_profile: str = "", *,
                 load_timeout_s: float = LOAD_TIMEOUT_S, userdata_rate_hz: float = DEFAULT_RATE_HZ) -> None:
        self.search_path = list(search_path)
        self.robot_profile = robot_profile
        self.supervised = supervised
        self.loader = loader
        self.on_done = on_done
        self.load_timeout_s = load_timeout_s
        self.userdata_rate_hz = userdata_rate_hz
        install_aliases()  # smach / flexbe_core state libraries in YAML behaviors import flex_nav's
        self.operator = OperatorPublisher()
        self._lock = threading.Lock()
        self._executor: Optional[BehaviorExecutor] = None
        self._thread: Optional[threading.Thread] = None
        self._loading: Optional[BackgroundLoad[_Built]] = None
        self._name = ""
        self._userdata: Optional[UserdataPublisher] = None
        self._publish_userdata = userdata_topic()
        self._command_sub = rospy.Subscriber("~command", BehaviorCommand, self._on_command, queue_size=10)
        self.operator.publish_idle("", "no behavior started", int(Autonomy.FULL))
        self.operator.publish_structure(structure_json(None, self.search_path))
        no_userdata(self._publish_userdata)

    # --- lifecycle -----------------------------------------------------------------------------------
    def start_local(self, source: str, autonomy: object = Autonomy.FULL,
                    parameters: Optional[Dict[str, Any]] = None, inputs: Optional[Dict[str, Any]] = None) -> str:
        """Load (bounded by ``load_timeout_s``), validate and start a behavior from a trusted source (``~behavior``):
        a name, a YAML file or ``py:package.module:Class``. Waits for the load; raises a FlexNavError if it fails.
        """
        spec: Union[str, BehaviorSource] = source if source.startswith(PYTHON_PREFIX) else BehaviorSource.local(source)
        return self._finish_load(self._begin_load(source, spec, autonomy, parameters, inputs))

    def start_remote(self, name: str, autonomy: object = Autonomy.FULL, parameters: Optional[Dict[str, Any]] = None,
                     inputs: Optional[Dict[str, Any]] = None, answer: Optional[Answer] = None) -> str:
        """Begin loading behavior ``name`` from the search path only (a name received over ROS); returns at once.

        ``answer(ok, message, pending)`` is called first with ``(True, "loading ...", True)``, then once more when
        the load ends or times out with the final answer (started, or why not; pending False). Raises ConfigError
        when the load cannot even begin (bad name, another behavior loads or runs): then nothing is answered.
        """
        source = BehaviorSource.remote(name)
        job = self._begin_load(name, source, autonomy, parameters, inputs)
        loading = f"loading behavior {name!r} (at most {self.load_timeout_s:g} s; the final answer follows)"
        if answer is not None:
            answer(True, loading, True)  # before the final answer can come

        def finish() -> None:
            try:
                ok, message = True, self._finish_load(job)
            except FlexNavError as err:
                ok, message = False, str(err) or type(err).__name__
            if answer is not None:
                answer(ok, message, False)

        threading.Thread(target=finish, name=f"start {name}", daemon=True).start()
        return loading

    def _begin_load(self, what: str, source: Union[str, BehaviorSource], autonomy: object,
                    parameters: Optional[Dict[str, Any]], inputs: Optional[Dict[str, Any]]) -> BackgroundLoad[_Built]:
        level = Autonomy.parse(autonomy)
        with self._lock:
            if self._thread is not None and self._thread.is_alive():
                raise ConfigError(f"behavior {self._name!r} is still running; stop it first")
            if self._loading is not None:
                raise ConfigError(
                    f"behavior {self._loading.what} is still loading ({self._loading.elapsed_s():.1f} s of at most "
                    f"{self.load_timeout_s:g} s); wait for its answer, or stop to cancel it"
                )
            job: BackgroundLoad[_Built] = BackgroundLoad(
                repr(what) if len(what) <= SHOWN_CHARS else _shown(what),
                lambda: self._build(source, level, dict(parameters or {}), dict(inputs or {})),
                lambda built: built.proxies.shutdown(),
                self.load_timeout_s,
            )
            self._loading = job
            job.start()
        return job

    def _build(self, source: Union[str, BehaviorSource], level: Autonomy, parameters: Dict[str, Any],
               inputs: Dict[str, Any]) -> _Built:
        """Runs in the load's worker thread: the behavior and its executor, not started yet."""
        # a running behavior's ticks hold a lockstep simulation (released in _run when it ends); its states'
        # velocity commands are announced with the same participant
        hold = LockstepParticipant("behavior")
        proxies = RosProxies(lockstep=hold)
        what = source if isinstance(source, str) else source.text
        clock = RosClock(lockstep=hold) if hold.enabled else RosClock()
        context = BehaviorContext(what, autonomy=level, supervised=self.supervised, clock=clock, proxies=proxies)
        try:
            if isinstance(source, str):  # py:package.module:Class, only ever from start_local
                behavior = build_behavior(flexbe_behavior_class(source[len(PYTHON_PREFIX):]), parameters=parameters,
                                          context=context)
            else:
                behavior = self.loader(source, self._yaml_parameters(source, parameters), self.search_path)
            context.name = behavior.name
            executor = BehaviorExecutor(behavior, inputs=inputs, context=context, should_stop=rospy.is_shutdown)
            structure = structure_json(behavior, self.search_path)
        except BaseException:
            proxies.shutdown()  # connections a state made while being built must not outlive a failed start
            raise
        return _Built(behavior, executor, proxies, level, structure)

    def _finish_load(self, job: BackgroundLoad[_Built]) -> str:
        """Wait (bounded) for ``job`` and start its behavior, unless the load failed or was cancelled meanwhile."""
        try:
            built = job.wait()
        except FlexNavError:
            with self._lock:
                if self._loading is job:
                    self._loading = None
            raise
        with self._lock:
            if self._loading is not job:  # stop cancelled it while its result was being handed over
                built.proxies.shutdown()
                raise BehaviorError(f"loading behavior {job.what} was cancelled: stopped by the operator")
            self._loading = None
            behavior, executor = built.behavior, built.executor
            self.operator.publish_structure(built.structure)
            self.operator.attach(executor.context.hooks, behavior.name, int(built.level))
            self._executor, self._name = executor, behavior.name
            if self._userdata is not None:
                self._userdata.stop()
            self._userdata = UserdataPublisher(executor, behavior.name, self._publish_userdata,
                                               rate_hz=self.userdata_rate_hz).start()
            self._thread = threading.Thread(
                target=self._run, args=(executor, built.proxies), name=f"behavior {behavior.name}", daemon=True
            )
            self._thread.start()
        return f"started behavior {behavior.name!r} at autonomy {built.level.name}"

    def _yaml_parameters(self, source: BehaviorSource, parameters: Dict[str, Any]) -> Dict[str, Any]:
        if not self.robot_profile:
            return dict(parameters)
        merged = with_robot_profile(parameters, declared_parameter_names(source, self.search_path),
                                    self.robot_profile)
        if merged != parameters:
            rospy.loginfo(f"behavior {source.text!r}: profile {self.robot_profile!r} (the robot's, ~robot_profile)")
        return merged

    def _run(self, executor: BehaviorExecutor, proxies: RosProxies) -> None:
        clock = executor.context.clock
        hold: Optional[LockstepParticipant] = getattr(clock, "lockstep", None)  # a RosClock's, in lockstep
        try:
            if hold is not None:
                wait_for_start_grid(clock, self._name)
            result = executor.run()
        finally:
            proxies.shutdown()
            if hold is not None:
                hold.release()
        rospy.loginfo(f"behavior {self._name!r} ended: {result.status.name} {result.outcome or ''} {result.reason}")
        if self.on_done is not None:
            self.on_done(result)

    def stop(self, timeout_s: float = STOP_TIMEOUT_S) -> str:
        """Cancel a load in progress, or preempt the running behavior and wait (bounded) until it exited its states."""
        with self._lock:
            job, self._loading = self._loading, None
            if job is not None:
                job.cancel("stopped by the operator")
                return f"cancelled loading behavior {job.what}"
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
        if self._userdata is not None:
            self._userdata.stop()
        self.operator.close()

    # --- commands ------------------------------------------------------------------------------------
    def _on_command(self, msg: BehaviorCommand) -> None:
        command, args = msg.command, list(msg.args)

        def answer(ok: bool, message: str, pending: bool = False) -> None:
            shown = " ".join(_shown(a) for a in [command, *args])
            (rospy.loginfo if ok else rospy.logwarn)(f"command {shown}: {message}")
            self.operator.publish_feedback(command, args, ok, message, pending)

        try:
            if command == "start":  # answered twice by start_remote: now ("loading", pending), when the load ends
                self.start_command(args, answer)
                return
            message = self.handle(command, args)
            ok = True
        except (FlexNavError, concurrent.futures.TimeoutError) as err:
            ok, message = False, str(err) or type(err).__name__
        answer(ok, message)

    def start_command(self, args: List[str], answer: Optional[Answer] = None) -> str:
        """``start NAME [autonomy=LEVEL] [KEY=VALUE ...]`` received over ROS: only a name on the search path."""
        if not args:
            raise ConfigError(f"start needs a behavior name (valid: {', '.join(list_behaviors(self.search_path))})")
        try:
            source = BehaviorSource.remote(args[0])
        except ConfigError as err:
            raise ConfigError(
                f"start takes the name of a behavior on the search path, not a file or a class: {err} "
                f"(valid: {', '.join(list_behaviors(self.search_path)) or 'none'})"
            ) from err
        options = parse_assignments(args[1:])
        autonomy = options.pop("autonomy", Autonomy.FULL)
        return self.start_remote(source.text, autonomy, options, answer=answer)

    def handle(self, command: str, args: List[str]) -> str:
        """Apply one operator command other than start; returns what was done, raises FlexNavError saying why not."""
        if command not in self.COMMANDS:
            raise ConfigError(choices_message("command", command[:SHOWN_CHARS], self.COMMANDS))
        if command == "start":
            raise ConfigError("start is answered twice: use start_command (or start_remote)")
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
