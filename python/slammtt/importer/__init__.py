"""slammtt-import: ROS 1 / ROS 2 bags and BreezySLAM text logs -> LCM logs of the stack's types
(docs/import.md). Modules: laser (LaserScan, REP 117), odometry, mount (tf), geometry,
rosbag (reading bags with rosbags), breezyslam (text format), output (the log), cli."""
