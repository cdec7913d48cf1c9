"""Following a path (no rospy): the control law and every rule around it that the controllers and follow servers use.

- ``pure_pursuit``   :class:`RegulatedPurePursuit`: regulated pure pursuit with a forward collision check
- ``path_obstacle``  the first obstacle on a path
- ``controller``     :class:`SafeFollower`: pure pursuit inside the safety rules (sensors, collisions, limits)
- ``progress``       progress along a path, tracked monotonically (the follow servers' lookahead)
- ``blocked``        an obstacle sitting on the path for a while
- ``yielding``       giving way to people walking across (moving-obstacle tracks)
- ``social_distance`` a speed limit keeping a distance from people; whose doing a contact was
- ``safety``         finite commands, fresh sensors, a stop after silence, the order of commands
- ``clock_watch``    a ROS clock that stops or jumps back
- ``operator_link``  the operator side's heartbeat
- ``topic_name``     legal ROS names, checked before anything subscribes
The ROS nodes in :mod:`flex_nav.nodes` wire these to topics and actions.
"""
