"""``twist_relay``: geometry_msgs/TwistStamped on ``cmd_vel_stamped`` -> geometry_msgs/Twist on ``cmd_vel``.

Flexible Navigation's controllers publish stamped commands (for logging); ordinary base drivers take a Twist. A
non-finite command is never forwarded: it is logged and a zero Twist goes out instead (a broken controller stops
the robot). Parameter ``~timeout`` [s] (0 = off, with a warning: then the base driver's own command timeout must
stop the robot; default 0.5): when no command arrived for this long after the last one and that one was moving, one
zero Twist is published (with a warning), so a crashed controller cannot leave the base driving on its last
command; silence after a stop (a controller's last word at its goal) is no fault. Controllers and behavior states
publish to the same topic from different nodes, whose messages have no order between them: a command stamped before
one already forwarded is dropped, and at equal stamps a stop wins
(:class:`~flex_nav.nav.control.safety.CommandOrder`). When ROS time moves backwards (a restarted simulation, a
looped bag) a zero Twist goes out and the order starts afresh, so the new timeline's commands get through; a
command stamped more than 1 s ahead of this node's clock (the old timeline's, sent by a node that has not seen the
jump yet) is dropped, so it cannot block them again. When ROS time stops advancing for longer than ``~timeout`` of
wall time (the simulator paused or crashed: every timeout on ROS time stands still with it), one zero Twist goes
out and nothing is forwarded until ROS time moves again (not in a lockstep simulation, ``/lockstep``: there ROS
time stands while the simulator waits for a node, and the robot stands with it). ``~heartbeat_timeout`` [s of wall
time] (0 = off, the default; see :mod:`flex_nav.ros.heartbeat`): when set, no heartbeat from the operator side for
that long -- the link to the computer running the behavior dropped -- sends one zero Twist and forwards nothing
until heartbeats come again (nothing at all before the first one). When the node shuts down (Ctrl-C, the launch
ending, ``rosnode kill``) it publishes a last zero Twist and forwards nothing after it. The checks run on a
wall-time thread, so they work while ROS time stands still.
"""

from __future__ import annotations

import threading
import time
from typing import Callable, Dict, List, Optional, Tuple

import rospy
from geometry_msgs.msg import Twist, TwistStamped

from flex_nav.nav.control.clock_watch import ClockChange, ClockWatch
from flex_nav.nav.control.safety import CommandOrder, CommandTimeout, twist_problem
from flex_nav.ros.heartbeat import HeartbeatListener
from flex_nav.ros.lockstep import lockstep_enabled
from flex_nav.ros.params import param_float, reject_unknown
from flex_nav.ros.proxies import SHUTDOWN_DRAIN_S, drain_publisher

LOG_THROTTLE_S = 1.0  # [s] wall: repeated messages of one kind are logged at most this often
CHECK_PERIOD_MIN_S = 0.01  # [s] wall: fastest check
CHECK_PERIOD_MAX_S = 0.05  # [s] wall: slowest check (a timeout of 0.5 s of ROS time is 0.25 s of wall at rtf 2)
FUTURE_STAMP_TOLERANCE_S = 1.0  # [s] commands stamped further ahead of this node's clock are not forwarded


class TwistRelay:
    def __init__(self) -> None:
        reject_unknown("~", ("timeout", "heartbeat_timeout"))
        timeout_s = param_float("~timeout", 0.5, 0.0, 3600.0)
        self._timeout = CommandTimeout(timeout_s)
        self._order = CommandOrder()
        self._lock = threading.Lock()
        # in a lockstep simulation ROS time stands while it waits for some node on purpose (and the robot with it)
        self._clock = ClockWatch(stall_timeout_s=0.0 if lockstep_enabled() else timeout_s)
        self.publisher = rospy.Publisher("cmd_vel", Twist, queue_size=1)
        self._heartbeat = HeartbeatListener(param_float("~heartbeat_timeout", 0.0, 0.0, 3600.0))
        self._link_lost = self._heartbeat.link.enabled  # nothing is forwarded before the first heartbeat
        self._shut_down = False
        self._logs: List[Tuple[Callable[[str], None], str]] = []  # written after the lock is released
        self._logged_at: Dict[str, float] = {}  # [s] wall: when a throttled kind of message was last logged
        self._last_now_s = rospy.get_time()
        self._clock.observe(self._last_now_s, time.monotonic())
        rospy.on_shutdown(self._on_shutdown)
        self.subscriber = rospy.Subscriber("cmd_vel_stamped", TwistStamped, self._on_command, queue_size=1,
                                           tcp_nodelay=True)
        if timeout_s == 0.0:
            rospy.logwarn("twist_relay: ~timeout 0: no zero Twist after the commands stop or when ROS time stops; "
                          "the base driver's own command timeout must stop the robot")
        self._period_s = min(CHECK_PERIOD_MAX_S, max(CHECK_PERIOD_MIN_S, timeout_s / 5.0))
        self._checker = threading.Thread(target=self._check_loop, name="twist_relay checks", daemon=True)
        self._checker.start()

    def _log(self, log: Callable[[str], None], message: str, throttle: Optional[str] = None) -> None:
        """Log ``message`` once the lock is released (lock held): a log call can block (see _look_at_clock).
        With ``throttle``, messages of that kind are logged at most every LOG_THROTTLE_S."""
        if throttle is not None:
            now_s = time.monotonic()
            if now_s - self._logged_at.get(throttle, -LOG_THROTTLE_S) < LOG_THROTTLE_S:
                return
            self._logged_at[throttle] = now_s
        self._logs.append((log, message))

    def _write_logs(self) -> None:
        if not self._logs:  # the usual case, per command: no second lock (a racy read: a log is at most late)
            return
        with self._lock:
            logs, self._logs = self._logs, []
        for log, message in logs:
            log(message)

    def _stop_base(self) -> None:
        """One zero Twist; no timeout is due after it until the next forwarded command (lock held)."""
        self._timeout.stopped()
        self.publisher.publish(Twist())

    def _look_at_clock(self) -> None:
        """Read ROS time into ``_last_now_s`` and act on a jump back, a stall or a resume (lock held). Every stop is
        published before it is logged: a log call can block (rospy asks the master when it logs, unless
        /rosout_disable_topics_generation is set, and the master may be across a dropped link)."""
        self._last_now_s = rospy.get_time()
        change = self._clock.observe(self._last_now_s, time.monotonic())
        if change is ClockChange.JUMPED_BACK:
            self._order.reset()
            self._stop_base()
            self._log(rospy.logwarn, f"twist_relay: ROS time moved backwards by {self._clock.jump_s:.2f} s; "
                      "published a zero Twist and forgot the stamps of the old timeline")
        elif change is ClockChange.STALLED:
            self._stop_base()
            self._log(rospy.logerr, f"twist_relay: ROS time has not advanced for {self._clock.stall_timeout_s:.2f} s "
                      "of wall time (simulator paused or gone?); published a zero Twist, forwarding nothing until it "
                      "moves again")
        elif change is ClockChange.RESUMED:
            self._log(rospy.logwarn, "twist_relay: ROS time moves again; forwarding commands")

    def _look_at_link(self) -> None:
        """Stop the base once when the operator's heartbeat is lost; forward again when it is back (lock held)."""
        lost = self._heartbeat.lost()
        if lost and not self._link_lost:
            self._stop_base()
            self._log(rospy.logerr, f"twist_relay: {self._heartbeat.why_lost()}; published a zero Twist, "
                      "forwarding nothing until it is back")
        elif not lost and self._link_lost:
            self._log(rospy.logwarn, f"twist_relay: operator heartbeat on {self._heartbeat.topic} heard; "
                      "forwarding commands")
        self._link_lost = lost

    def _on_command(self, msg: TwistStamped) -> None:
        try:
            self._relay(msg)
        finally:
            self._write_logs()

    def _relay(self, msg: TwistStamped) -> None:
        lin, ang = msg.twist.linear, msg.twist.angular
        problem = twist_problem((lin.x, lin.y, lin.z), (ang.x, ang.y, ang.z))
        with self._lock:
            if self._shut_down:
                return
            self._look_at_clock()
            if problem is not None:
                self._log(rospy.logerr, f"twist_relay: {problem}; dropped, publishing a zero Twist instead",
                          throttle="non-finite")
                self._stop_base()
                return
            if self._clock.stalled or self._link_lost:
                why = "ROS time stands still" if self._clock.stalled else "the operator's heartbeat is lost"
                self._log(rospy.logwarn, f"twist_relay: dropped a command: {why}", throttle="dropped")
                return
            moving = any(v != 0.0 for v in (lin.x, lin.y, lin.z, ang.x, ang.y, ang.z))
            stamp_s = msg.header.stamp.to_sec()
            if stamp_s > self._last_now_s + FUTURE_STAMP_TOLERANCE_S:  # an old timeline's, or a skewed clock
                ahead_s = stamp_s - self._last_now_s
                self._log(rospy.logwarn, f"twist_relay: dropped a command stamped {ahead_s:.1f} s ahead of this "
                                         "node's clock (time moved backwards, or clocks differ)", throttle="ahead")
                return
            if not self._order.admit(stamp_s, moving):
                self._log(rospy.logdebug, "twist_relay: dropped a command stamped before one already forwarded")
                return
            if moving:
                self._timeout.command(self._last_now_s)
            else:  # a stop (a controller's last word at its goal): the base stands, no timeout zero is due
                self._timeout.stopped()
            self.publisher.publish(msg.twist)

    def _check_loop(self) -> None:
        """Wall-time checks: the command timeout (on ROS time), ROS time itself, the operator's heartbeat."""
        while not rospy.is_shutdown():
            time.sleep(self._period_s)
            try:
                with self._lock:
                    if self._shut_down:
                        return
                    self._check()
                self._write_logs()
            except Exception as err:  # the checks must go on
                rospy.logerr_throttle(5.0, f"twist_relay: check failed: {err!r}")

    def _check(self) -> None:
        self._look_at_clock()
        self._look_at_link()
        if self._timeout.due(self._last_now_s):
            self.publisher.publish(Twist())
            self._log(rospy.logwarn,
                      f"twist_relay: no command for {self._timeout.timeout_s:.2f} s; published a zero Twist")

    def _on_shutdown(self) -> None:
        """The node is stopping (Ctrl-C, roslaunch ending, rosnode kill): the base gets a zero Twist, not the
        last command until its driver's own timeout; nothing is forwarded after it."""
        with self._lock:
            self._shut_down = True
            self.publisher.publish(Twist())
        drain_publisher(self.publisher, time.monotonic() + SHUTDOWN_DRAIN_S)
