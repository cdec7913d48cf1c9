"""Every message of a topic, kept for a rostest node to wait on (imported from this directory, not a test itself)."""

import threading
from typing import Any, Callable, List, Optional

import rospy


class MessageLog:
    """Every message on ``topic`` since the subscription (``msgs``, in arrival order), with a bounded wait for one
    that meets a condition. A subclass may keep more than the message (:meth:`record`) and time its waits on
    another clock than ROS time (:meth:`now_s`, e.g. the wall clock where a test fakes ROS time)."""

    def __init__(self, topic: str, msg_type: type, *, queue_size: Optional[int] = 10, wait_s: float = 10.0,
                 poll_s: float = 0.1) -> None:
        """``queue_size``: the subscriber's (None: unbounded); ``wait_s`` [s]: the longest wait of :meth:`wait_for`
        unless told; ``poll_s`` [s]: its longest sleep."""
        self.cond = threading.Condition()
        self.msgs: List[Any] = []
        self.wait_s = wait_s
        self.poll_s = poll_s
        self.topic = topic
        self.sub = rospy.Subscriber(topic, msg_type, self.on_msg, queue_size=queue_size)

    def record(self, msg: Any) -> Any:
        """What is kept of a message."""
        return msg

    def now_s(self) -> float:
        return float(rospy.get_time())

    def on_msg(self, msg: Any) -> None:
        with self.cond:
            self.msgs.append(self.record(msg))
            self.cond.notify_all()

    def count(self) -> int:
        with self.cond:
            return len(self.msgs)

    def since(self, index: int) -> List[Any]:
        with self.cond:
            return list(self.msgs[index:])

    def wait_for(self, condition: Callable[[Any], bool], after: int = 0, timeout_s: Optional[float] = None) -> Any:
        """The first entry from index ``after`` on that meets ``condition``; None when none did within ``timeout_s``
        [s] (``wait_s`` when None)."""
        deadline = self.now_s() + (self.wait_s if timeout_s is None else timeout_s)
        with self.cond:
            while True:
                for entry in self.msgs[after:]:
                    if condition(entry):
                        return entry
                left = deadline - self.now_s()
                if left <= 0:
                    return None
                self.cond.wait(min(left, self.poll_s))

    def newest(self, condition: Callable[[Any], bool], timeout_s: Optional[float] = None) -> Any:
        """The newest entry meeting ``condition`` once one did; AssertionError naming the last entries when none did
        within ``timeout_s`` [s] (``wait_s`` when None)."""
        wait_s = self.wait_s if timeout_s is None else timeout_s
        if self.wait_for(condition, timeout_s=wait_s) is None:
            received = self.since(0)
            raise AssertionError(
                f"no message on {self.topic} meeting the condition within {wait_s} s; {len(received)} received, "
                f"the last: {received[-5:]}"
            )
        return [entry for entry in self.since(0) if condition(entry)][-1]
