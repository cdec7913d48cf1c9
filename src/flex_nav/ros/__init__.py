"""ROS adapters: the only part of ``flex_nav`` that imports rospy. Nodes are thin wrappers over pure modules."""
