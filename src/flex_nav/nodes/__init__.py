"""The ROS nodes, one module per node (``scripts/`` holds their thin launchers). Nodes wire the pure parts
(:mod:`flex_nav.behavior`, :mod:`flex_nav.nav`, :mod:`flex_nav.perception`) to ROS through the adapters in
:mod:`flex_nav.ros`; nothing below imports a node."""
