"""Pure logic of the follow servers and controllers (no rospy): progress along a path, sensor freshness,
command safety. The ROS nodes in :mod:`flex_nav.ros` wire these to topics and actions."""
