"""Pure navigation algorithms (no rospy): maps, costmaps, global planning, path following.

- ``grid_map``        :class:`GridMap`, an occupancy grid in OccupancyGrid conventions, world <-> cell
- ``map_io``          map_server-format YAML + PGM/PNG load and save
- ``costmap_grid``    cost values (costmap_2d's), cost -> OccupancyGrid translation, costmap geometry
- ``static_layer``    map values -> costs
- ``obstacle_layer``  laser-scan marking and ray-trace clearing, bumper marks
- ``raytrace``        compiled Bresenham ray tracing
- ``inflation``       costmap_2d inflation on an exact distance transform
- ``costmap``         the layered costmap (global or rolling window), bounded updates, reset
- ``astar``           compiled A* kernel (4-ary heap + equal-f stack), line-of-sight shortcuts
- ``planner``         :class:`GridPlanner`: optimal cost-aware planning with typed results
- ``path``            path length, closest point, lookahead point, pruning (distances in metres)
- ``pure_pursuit``    :class:`RegulatedPurePursuit`: regulated pure pursuit with a forward collision check
"""
