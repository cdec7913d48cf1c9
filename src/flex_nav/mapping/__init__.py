"""2D lidar graph SLAM and frontier exploration on occupancy grids, without ROS (the mapper node and the explore
behavior are built on it).
"""
