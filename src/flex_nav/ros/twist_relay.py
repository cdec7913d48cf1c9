"""``twist_relay``: geometry_msgs/TwistStamped on ``cmd_vel_stamped`` -> geometry_msgs/Twist on ``cmd_vel``.

Flexible Navigation's controllers publish stamped commands (for logging); ordinary base drivers take a
Twist. A non-finite command is never forwarded: it is logged and a zero Twist goes out instead (a broken
controller stops the robot). Parameter ``~timeout`` [s] (0 = off, with a warning: then the base driver's own
command timeout must stop the robot; default 0.5): when no command arrived for this long after the last one,
one zero Twist is published, so a crashed controller cannot leave the base driving on its last command.
Controllers and behavior states publish to the same topic from different nodes, whose messages have no order
between them: a command stamped before one already forwarded is dropped, and at equal stamps a stop wins
(:class:`~flex_nav.follow.safety.CommandOrder`). When ROS time moves backwards (a restarted simulation, a
looped bag) a zero Twist goes out and the order starts afresh, so the new timeline's commands get through; a
command stamped more than 1 s ahead of this node's clock (the old timeline's, sent by a node that has not seen
the jump yet) is dropped, so it cannot block them again. When the node shuts down (Ctrl-C, the launch ending,
``rosnode kill``) it publishes a last zero Twist and forwards nothing after it.
"""

from __future__ import annotations

import threading
import time

import rospy
from geometry_msgs.msg import Twist, TwistStamped

from flex_nav.follow.safety import CommandOrder, CommandTimeout, twist_problem
from flex_nav.ros.params import param_float, reject_unknown
from flex_nav.ros.proxies import SHUTDOWN_DRAIN_S, drain_publisher

CHECK_PERIOD_MIN_S = 0.01  # [s] fastest timeout check
FUTURE_STAMP_TOLERANCE_S = 1.0  # [s] commands stamped further ahead of this node's clock are not forwarded


class TwistRelay:
    def __init__(self) -> None:
        reject_unknown("~", ("timeout",))
        timeout_s = param_float("~timeout", 0.5, 0.0, 3600.0)
        self._timeout = CommandTimeout(timeout_s)
        self._order = CommandOrder()
        self._lock = threading.Lock()
        self.publisher = rospy.Publisher("cmd_vel", Twist, queue_size=1)
        self.subscriber = rospy.Subscriber("cmd_vel_stamped", TwistStamped, self._on_command, queue_size=1,
                                           tcp_nodelay=True)
        self._timer = None
        self._shut_down = False
        rospy.on_shutdown(self._on_shutdown)
        self._last_now_s = rospy.get_time()
        if timeout_s > 0.0:
            period_s = max(CHECK_PERIOD_MIN_S, timeout_s / 5.0)
            self._timer = rospy.Timer(rospy.Duration(period_s), self._on_check, reset=True)  # survives time jumps
        else:
            rospy.logwarn("twist_relay: ~timeout 0: no zero Twist after the commands stop; the base driver's own "
                          "command timeout must stop the robot")

    def _clock_went_back(self) -> bool:
        """True (once) when ROS time moved backwards since the last call; the order starts afresh then."""
        now_s = rospy.get_time()
        back = now_s < self._last_now_s
        self._last_now_s = now_s
        if back:
            rospy.logwarn("twist_relay: ROS time moved backwards; publishing a zero Twist and forgetting the "
                          "stamps of the old timeline")
            self._order.reset()
            self._timeout.stopped()
            self.publisher.publish(Twist())
        return back

    def _on_command(self, msg: TwistStamped) -> None:
        lin, ang = msg.twist.linear, msg.twist.angular
        problem = twist_problem((lin.x, lin.y, lin.z), (ang.x, ang.y, ang.z))
        with self._lock:
            if self._shut_down:
                return
            self._clock_went_back()
            if problem is not None:
                rospy.logerr_throttle(1.0, f"twist_relay: {problem}; dropped, publishing a zero Twist instead")
                self._timeout.stopped()
                self.publisher.publish(Twist())
                return
            moving = any(v != 0.0 for v in (lin.x, lin.y, lin.z, ang.x, ang.y, ang.z))
            stamp_s = msg.header.stamp.to_sec()
            if stamp_s > self._last_now_s + FUTURE_STAMP_TOLERANCE_S:  # an old timeline's, or a skewed clock
                ahead_s = stamp_s - self._last_now_s
                rospy.logwarn_throttle(1.0, f"twist_relay: dropped a command stamped {ahead_s:.1f} s ahead of this "
                                            "node's clock (time moved backwards, or clocks differ)")
                return
            if not self._order.admit(stamp_s, moving):
                rospy.logdebug("twist_relay: dropped a command stamped before one already forwarded")
                return
            self._timeout.command(self._last_now_s)  # read by _clock_went_back above
            self.publisher.publish(msg.twist)

    def _on_check(self, _event: rospy.timer.TimerEvent) -> None:
        with self._lock:
            if self._clock_went_back():
                return
            if self._timeout.due(self._last_now_s):
                rospy.logwarn(f"twist_relay: no command for {self._timeout.timeout_s:.2f} s; publishing a zero Twist")
                self.publisher.publish(Twist())

    def _on_shutdown(self) -> None:
        """The node is stopping (Ctrl-C, roslaunch ending, rosnode kill): the base gets a zero Twist, not the
        last command until its driver's own timeout; nothing is forwarded after it."""
        with self._lock:
            self._shut_down = True
            self.publisher.publish(Twist())
        drain_publisher(self.publisher, time.monotonic() + SHUTDOWN_DRAIN_S)
