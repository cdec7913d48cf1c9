"""ROS adapters: proxies, parameters, frames, conversions, the goal server, topic paths, the costmap's ROS glue,
clocks. With :mod:`flex_nav.nodes` the only part of ``flex_nav`` that imports rospy; adapters import no node."""
