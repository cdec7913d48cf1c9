"""Pure navigation algorithms (no rospy), in three parts, and the geometry they share.

- :mod:`flex_nav.nav.costmap`   maps and layered costmaps: what is where and what it costs
- :mod:`flex_nav.nav.planning`  global planning on a costmap (A*, typed results)
- :mod:`flex_nav.nav.control`   following a path: regulated pure pursuit and the safety rules around it
- ``angles``      the one angle wrap
- ``planar``      (x, y, yaw) transforms of poses and paths
- ``path``        path length, closest point, lookahead point, pruning (distances in metres)
- ``pose_checks`` finite, normalised poses
- ``warm_cache``  compiles the numba kernels into their cache (run by the installer)
"""
