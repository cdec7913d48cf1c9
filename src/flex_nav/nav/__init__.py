"""Pure navigation algorithms (no rospy): maps, costmaps, global planning, path following.

- ``grid_map``      :class:`GridMap`, an occupancy grid in OccupancyGrid conventions, world <-> cell
- ``map_io``        map_server-format YAML + PGM/PNG load and save
"""
