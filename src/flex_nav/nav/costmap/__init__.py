"""Maps and costmaps (no rospy).

- ``grid_map``        :class:`GridMap`, an occupancy grid in OccupancyGrid conventions, world <-> cell
- ``map_io``          map_server-format YAML + PGM/PNG load and save
- ``costmap_grid``    cost values (costmap_2d's), cost -> OccupancyGrid translation, costmap geometry
- ``static_layer``    map values -> costs
- ``obstacle_layer``  laser-scan marking and ray-trace clearing, bumper marks
- ``bumper_layer``    bumper contacts kept in the costmap
- ``bumper_contacts`` where a bumper touched something, from bumper zone states
- ``memory_layer``    obstacles found heavy, remembered LETHAL: decay, forgotten when a scan sees them gone, cleared
- ``raytrace``        compiled Bresenham ray tracing
- ``inflation``       costmap_2d inflation on an exact distance transform
- ``layered``         :class:`Costmap`: the layered costmap (global or rolling window), bounded updates, reset
"""
