"""flex_nav: Flexible Navigation for ROS 1.

Layout of the import package (one concept per module):

- ``flex_nav.exceptions``  the typed exceptions every part raises
- ``flex_nav.msg``         action classes generated from ``action/*.action`` (by tools/genmsg.py or catkin)
- ``flex_nav.rosutil``     small helpers for nodes and tests that talk to a real master

Pure modules never import rospy; ROS nodes in ``scripts/`` are thin wrappers around them.
"""

__version__ = "0.1.0"
