"""Perception for obstacle-aware navigation: is the region in front of the robot a person, a movable object or clear?
And what moves around the robot (laser tracks)?

ROS-free core (never imports rospy); the node is :mod:`flex_nav.nodes.obstacle_classifier`.

| module | what |
| --- | --- |
| ``labels`` | the three labels (+ ``unknown``) and the roles a detector class can map to |
| ``image`` | a ``sensor_msgs/Image``-like buffer (rgb8/bgr8/rgba8/bgra8/mono8) -> an RGB array, no cv_bridge |
| ``roi`` | the region of interest (fractions of the image) in front of the robot |
| ``preprocess`` | classifier input (crop, resize, normalise) and YOLO letterbox (and its inverse) |
| ``onnx_model`` | onnxruntime sessions on the CPU with one thread, loading errors that name the file |
| ``classifier`` | :class:`ObstacleClassifier`: the project's own CNN (``models/obstacle_classifier.onnx``) |
| ``yolo`` | YOLOv8-family output decoding (both ultralytics layouts), class-wise NMS, :class:`YoloObstacleDetector` |
| ``smoothing`` | :class:`MajorityVote`: the majority of the last N frames, as in the thesis (N = 5) |
| ``factory`` | building either model kind from a validated :class:`PerceptionConfig` |
| ``scan_segments`` | laser scan points cut into segments of small bodies (centre and radius from the visible front) |
| ``static_mask`` | which scan points the static map explains (dropped before tracking) |
| ``moving_obstacles`` | :class:`MovingObstacleTracker`: constant-velocity Kalman tracks (position, velocity, radius) |
| ``lidar_shape`` | the lidar's cue of the object ahead: box (face, corner) or a person (moves; legs, body by switch) |
| ``fusion`` | camera class + lidar shape -> one decision by a documented rule (or look again, bounded) |
"""
