"""Global planning (no rospy).

- ``astar``    compiled A* kernel (4-ary heap + equal-f stack), line-of-sight shortcuts
- ``planner``  :class:`GridPlanner`: optimal cost-aware planning with typed results
"""
