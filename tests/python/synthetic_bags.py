"""Small ROS 1 / ROS 2 bags written by rosbags' writers for the importer's tests: LaserScan,
Odometry, tf and PoseArray messages with chosen values."""

import math

import numpy as np
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import StoragePlugin, Writer as Writer2
from rosbags.typesys import Stores, get_typestore, get_types_from_msg

# tf2_msgs/TFMessage (ROS's definition; not in rosbags' ROS 1 store)
TF_MESSAGE_MSG = "geometry_msgs/TransformStamped[] transforms\n"


def store(ros_version):
    if ros_version == 1:
        ts = get_typestore(Stores.ROS1_NOETIC)
        ts.register(get_types_from_msg(TF_MESSAGE_MSG, "tf2_msgs/msg/TFMessage"))
        return ts
    return get_typestore(Stores.ROS2_HUMBLE)


class Bag:
    """Collects (topic, msgtype, bag_time_ns, message) and writes them as a bag."""

    def __init__(self, ros_version=1):
        self.ros_version = ros_version
        self.ts = store(ros_version)
        self.messages = []

    def _t(self, name):
        return self.ts.types[name]

    def header(self, stamp_us, frame):
        Header = self._t("std_msgs/msg/Header")
        Time = self._t("builtin_interfaces/msg/Time")
        stamp = Time(sec=int(stamp_us // 1_000_000), nanosec=int(stamp_us % 1_000_000) * 1000)
        if self.ros_version == 1:
            return Header(seq=0, stamp=stamp, frame_id=frame)
        return Header(stamp=stamp, frame_id=frame)

    def add(self, topic, message, bag_time_us):
        self.messages.append((topic, message.__msgtype__, int(bag_time_us) * 1000, message))

    def scan(self, topic, stamp_us, ranges, frame="laser", angle_min=-1.0, increment=0.01,
             range_min=0.05, range_max=10.0, time_increment=1e-4, intensities=(),
             bag_time_us=None):
        LaserScan = self._t("sensor_msgs/msg/LaserScan")
        ranges = np.asarray(ranges, dtype=np.float32)
        message = LaserScan(
            header=self.header(stamp_us, frame), angle_min=angle_min,
            angle_max=angle_min + increment * max(len(ranges) - 1, 0), angle_increment=increment,
            time_increment=time_increment, scan_time=0.1, range_min=range_min,
            range_max=range_max, ranges=ranges,
            intensities=np.asarray(intensities, dtype=np.float32))
        self.add(topic, message, stamp_us if bag_time_us is None else bag_time_us)

    def odometry(self, topic, stamp_us, x, y, yaw, v, w, bag_time_us=None):
        t = self._t
        q = t("geometry_msgs/msg/Quaternion")(x=0.0, y=0.0, z=math.sin(yaw / 2),
                                               w=math.cos(yaw / 2))
        pose = t("geometry_msgs/msg/PoseWithCovariance")(
            pose=t("geometry_msgs/msg/Pose")(
                position=t("geometry_msgs/msg/Point")(x=x, y=y, z=0.0), orientation=q),
            covariance=np.zeros(36))
        twist = t("geometry_msgs/msg/TwistWithCovariance")(
            twist=t("geometry_msgs/msg/Twist")(
                linear=t("geometry_msgs/msg/Vector3")(x=v, y=0.0, z=0.0),
                angular=t("geometry_msgs/msg/Vector3")(x=0.0, y=0.0, z=w)),
            covariance=np.zeros(36))
        message = t("nav_msgs/msg/Odometry")(header=self.header(stamp_us, "odom"),
                                             child_frame_id="base_link", pose=pose, twist=twist)
        self.add(topic, message, stamp_us if bag_time_us is None else bag_time_us)

    def transform(self, stamp_us, parent, child, xyz, quaternion_xyzw):
        t = self._t
        return t("geometry_msgs/msg/TransformStamped")(
            header=self.header(stamp_us, parent), child_frame_id=child,
            transform=t("geometry_msgs/msg/Transform")(
                translation=t("geometry_msgs/msg/Vector3")(x=xyz[0], y=xyz[1], z=xyz[2]),
                rotation=t("geometry_msgs/msg/Quaternion")(
                    x=quaternion_xyzw[0], y=quaternion_xyzw[1], z=quaternion_xyzw[2],
                    w=quaternion_xyzw[3])))

    def tf(self, topic, stamp_us, transforms):
        message = self._t("tf2_msgs/msg/TFMessage")(transforms=list(transforms))
        self.add(topic, message, stamp_us)

    def pose_array(self, topic, stamp_us, points, frame, bag_time_us):
        t = self._t
        poses = [t("geometry_msgs/msg/Pose")(
            position=t("geometry_msgs/msg/Point")(x=float(x), y=float(y), z=0.0),
            orientation=t("geometry_msgs/msg/Quaternion")(x=0.0, y=0.0, z=0.0, w=1.0))
            for x, y in points]
        message = t("geometry_msgs/msg/PoseArray")(header=self.header(stamp_us, frame),
                                                   poses=poses)
        self.add(topic, message, bag_time_us)

    def write(self, path, storage="sqlite3"):
        """A ROS 1 .bag (ros_version 1) or a ROS 2 bag folder (sqlite3 or mcap)."""
        ordered = sorted(self.messages, key=lambda m: m[2])  # (stable: ties keep order)
        if self.ros_version == 1:
            writer = Writer1(path)
        else:
            plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
            writer = Writer2(path, version=9, storage_plugin=plugin)
        with writer:
            connections = {}
            for topic, msgtype, _, _ in ordered:
                if topic not in connections:
                    connections[topic] = writer.add_connection(topic, msgtype, typestore=self.ts)
            for topic, msgtype, time_ns, message in ordered:
                if self.ros_version == 1:
                    data = self.ts.serialize_ros1(message, msgtype)
                else:
                    data = self.ts.serialize_cdr(message, msgtype)
                writer.write(connections[topic], time_ns, data)
        return path


def quaternion_yaw(yaw):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def quaternion_roll_yaw(roll, yaw):
    """Rz(yaw) * Rx(roll) as (x, y, z, w)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (cy * sr, sy * sr, sy * cr, cy * cr)
