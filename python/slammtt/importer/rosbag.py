"""ROS 1 bags and ROS 2 bags (sqlite3 or MCAP storage) -> the stack's messages, read with the
`rosbags` library (its AnyReader reads both ROS versions; no bag parsing of our own).

Mapped (channel keys of --channel in brackets):
- sensor_msgs/LaserScan of one topic -> laser_scan_t [laser_scan] (laser.py: REP 117);
- nav_msgs/Odometry of one topic -> odometry_t [odometry] (odometry.py);
- geometry_msgs/PoseArray of the labels topic (leg_tracker's /leg_cluster_positions) ->
  leg_labels_t [leg_labels]: the positions' x, y, in the laser frame; utime = the labelled
  scan's. A label message whose stamp is 0 (as in the leg_tracker training bags) labels the next
  scan of the laser topic in bag order; one with a stamp labels the scan with that stamp. Labels
  in another frame are moved into the laser frame by the static transforms, or skipped;
- tf2_msgs/TFMessage on /tf_static and /tf -> the laser mount (mount.py), nothing in the log.
utime = header.stamp in microseconds (floor), or the bag's receive time with
time_source="bag".
"""

import dataclasses
import pathlib

import numpy as np

from slammtt.importer import laser, odometry
from slammtt.importer.mount import Mount, TransformTree, frame_name

LASER_SCAN = "sensor_msgs/msg/LaserScan"
ODOMETRY = "nav_msgs/msg/Odometry"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
POSE_ARRAY = "geometry_msgs/msg/PoseArray"
DEFAULT_LABELS_TOPIC = "/leg_cluster_positions"
# Far above the legs one scan can show (the training bags have at most 4); more is a corrupt
# message.
MAX_LABELS_PER_SCAN = 1000


class BagError(Exception):
    """A bag that cannot be read, or a selection that does not exist (one line)."""


@dataclasses.dataclass
class Selection:
    laser_topic: str = None        # None: the first LaserScan topic
    odometry_topic: str = None     # None: the first Odometry topic
    use_odometry: bool = True
    labels_topic: str = None       # None: /leg_cluster_positions when it is a PoseArray topic
    use_labels: bool = True
    time_source: str = "header"    # or "bag"
    base_frame: str = "base_link"
    wheel_track_m: float = None


@dataclasses.dataclass
class Label:
    utime: int
    x_m: np.ndarray
    y_m: np.ndarray


@dataclasses.dataclass
class BagContent:
    """What was read from a bag, before the mount is applied."""
    description: str = ""
    notes: list = dataclasses.field(default_factory=list)       # info lines
    warnings: list = dataclasses.field(default_factory=list)
    laser_topic: str = ""
    laser_frame: str = ""
    labels_topic: str = ""
    scans: list = dataclasses.field(default_factory=list)       # laser.Scan, bag order
    odometry: list = dataclasses.field(default_factory=list)    # odometry.Odometry, bag order
    labels: list = dataclasses.field(default_factory=list)      # Label, bag order
    tf_mount: Mount = None
    skipped: dict = dataclasses.field(default_factory=dict)     # what -> [count, first reason]

    def skip(self, what, reason):
        entry = self.skipped.setdefault(what, [0, reason])
        entry[0] += 1


def bag_path(path):
    """The path AnyReader takes: a ROS 1 .bag file, or a ROS 2 bag's folder (a .db3 / .mcap file
    inside a folder with metadata.yaml stands for its folder)."""
    path = pathlib.Path(path)
    if path.is_file() and path.suffix in (".db3", ".mcap") and \
            (path.parent / "metadata.yaml").exists():
        return path.parent
    return path


def _reader(path):
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore
    # ROS 2 bags without message definitions (sqlite3 before Iron) are read with Humble's
    # types; LaserScan, Odometry, TFMessage and PoseArray are the same in every ROS 2 release.
    return AnyReader([bag_path(path)], default_typestore=get_typestore(Stores.ROS2_HUMBLE))


def _stamp_utime(stamp):
    return int(stamp.sec) * 1_000_000 + int(stamp.nanosec) // 1000


def _choose(connections, msgtype, wanted, option, kind, content, required):
    topics = []
    for c in connections:
        if c.msgtype == msgtype and c.topic not in topics:
            topics.append(c.topic)
    if wanted is not None:
        if wanted not in topics:
            others = ", ".join(topics) if topics else "none"
            raise BagError(f"{option} {wanted}: no {kind} topic of that name "
                           f"({kind} topics: {others})")
        content.notes.append(f"{kind} topic {wanted} (chosen by {option})")
        return wanted
    if not topics:
        if required:
            present = ", ".join(sorted({f"{c.topic} ({c.msgtype})" for c in connections}))
            raise BagError(f"no {kind} topic in the bag (topics: {present or 'none'})")
        return None
    if len(topics) == 1:
        content.notes.append(f"{kind} topic {topics[0]} (the only one)")
    else:
        content.notes.append(f"{kind} topic {topics[0]}: the first of {len(topics)} "
                             f"({', '.join(topics)}); choose another with {option}")
    return topics[0]


def read_bag(path, selection):
    """BagContent of the bag at `path`; BagError (one line) when it cannot be read."""
    try:
        with _reader(path) as reader:
            return _read(reader, selection)
    except BagError:
        raise
    except Exception as error:  # rosbags raises its own errors, and OSError, KeyError...
        raise BagError(f"cannot read the bag ({type(error).__name__}: {error})") from None


def _read(reader, selection):
    content = BagContent()
    connections = list(reader.connections)
    version = "ROS 1" if getattr(reader, "is2", False) is False else "ROS 2"
    content.description = version
    laser_topic = _choose(connections, LASER_SCAN, selection.laser_topic, "--laser-topic",
                          "sensor_msgs/LaserScan", content, required=True)
    odometry_topic = None
    if selection.use_odometry:
        odometry_topic = _choose(connections, ODOMETRY, selection.odometry_topic,
                                 "--odometry-topic", "nav_msgs/Odometry", content,
                                 required=selection.odometry_topic is not None)
        if odometry_topic is None:
            content.notes.append("no odometry (no nav_msgs/Odometry topic)")
    labels_topic = None
    if selection.use_labels:
        wanted = selection.labels_topic
        pose_topics = {c.topic for c in connections if c.msgtype == POSE_ARRAY}
        if wanted is None and DEFAULT_LABELS_TOPIC in pose_topics:
            wanted = DEFAULT_LABELS_TOPIC
        if wanted is not None:
            if wanted not in pose_topics:
                raise BagError(f"--labels-topic {wanted}: no geometry_msgs/PoseArray topic of "
                               f"that name (PoseArray topics: "
                               f"{', '.join(sorted(pose_topics)) or 'none'})")
            labels_topic = wanted
            content.labels_topic = wanted
            content.notes.append(f"leg labels from {labels_topic}")
    content.laser_topic = laser_topic
    content.laser_frame = _first_frame(reader, connections, laser_topic, content)

    tree = _read_transforms(reader, connections, content)
    _read_messages(reader, connections, selection, laser_topic, odometry_topic, labels_topic,
                   tree, content)
    if content.laser_frame:
        base = frame_name(selection.base_frame)
        found = tree.lookup(base, content.laser_frame)
        if found is not None:
            transform, source = found
            content.tf_mount = Mount.from_transform(
                transform, f"static transform {base} -> {content.laser_frame} from {source}")
        elif tree.frames():
            content.notes.append(f"no static transform {base} -> {content.laser_frame} in the "
                                 f"bag's tf (frames: {', '.join(sorted(tree.frames()))})")
    return content


def _messages(reader, connections):
    """The messages of these connections in bag order (none for an empty list, where rosbags
    would give every connection's)."""
    if not connections:
        return iter(())
    return reader.messages(connections=connections)


def _first_frame(reader, connections, topic, content):
    laser_connections = [c for c in connections if c.topic == topic and c.msgtype == LASER_SCAN]
    for connection, _, raw in _messages(reader, laser_connections):
        try:
            return frame_name(reader.deserialize(raw, connection.msgtype).header.frame_id)
        except Exception:
            continue   # counted in the main pass
    return ""


def _read_transforms(reader, connections, content):
    tree = TransformTree()
    tf_connections = [c for c in connections if c.msgtype == TF_MESSAGE and
                      c.topic in ("/tf", "/tf_static", "tf", "tf_static")]
    # (reader.messages(connections=[]) would read every connection)
    for connection, _, raw in _messages(reader, tf_connections):
        try:
            message = reader.deserialize(raw, connection.msgtype)
        except Exception as error:
            content.skip("tf messages (undecodable)", str(error))
            continue
        for transform in message.transforms:
            tree.add(transform, static=connection.topic.lstrip("/") == "tf_static")
    content.warnings.extend(tree.conflicts)
    if tree.rejected:
        content.warnings.append(f"{tree.rejected} transforms were not rigid motions (a zero "
                                "or non-finite quaternion or translation) and were ignored")
    return tree


def _read_messages(reader, connections, selection, laser_topic, odometry_topic, labels_topic,
                   tree, content):
    """The scans, odometry and labels of the chosen topics, in bag order, into `content`."""
    handlers = _MessageHandlers(selection, tree, content, labels_topic)
    by_topic = {(laser_topic, LASER_SCAN): handlers.scan,
                (odometry_topic, ODOMETRY): handlers.odometry,
                (labels_topic, POSE_ARRAY): handlers.label}
    chosen = [c for c in connections if (c.topic, c.msgtype) in by_topic]
    for connection, bag_time_ns, raw in _messages(reader, chosen):
        try:
            message = reader.deserialize(raw, connection.msgtype)
            stamp = _stamp_utime(message.header.stamp)
        except Exception as error:
            content.skip(f"{connection.topic} messages (undecodable)", str(error))
            continue
        utime = stamp if selection.time_source == "header" else bag_time_ns // 1000
        by_topic[(connection.topic, connection.msgtype)](connection.topic, message, stamp, utime)
    handlers.finish()


class _MessageHandlers:
    """One handler per kind of message; labels wait for their scan (module docstring)."""

    def __init__(self, selection, tree, content, labels_topic):
        self.selection = selection
        self.tree = tree
        self.content = content
        self.labels_topic = labels_topic
        self.pending_labels = []   # labels with stamp 0, waiting for the next scan
        self.stamped_labels = []   # labels with a stamp, for the scan of that stamp

    def scan(self, topic, message, _, utime):
        content = self.content
        frame = frame_name(message.header.frame_id)
        if frame != content.laser_frame:
            content.skip(f"{topic} scans in another frame than {content.laser_frame}",
                         f"frame {frame}")
            return
        try:
            scan = laser.scan_from_laser_scan(message, utime)
        except laser.ScanRefused as error:
            content.skip(f"{topic} scans refused", str(error))
            return
        content.scans.append(scan)
        for label in self.pending_labels:
            label.utime = scan.utime
            content.labels.append(label)
        self.pending_labels = []

    def odometry(self, topic, message, _, utime):
        try:
            self.content.odometry.append(
                odometry.odometry_from_ros(message, utime, self.selection.wheel_track_m))
        except odometry.OdometryRefused as error:
            self.content.skip(f"{topic} messages refused", str(error))

    def label(self, _, message, stamp, utime):
        label = _label(message, self.tree, self.content)
        if label is None:
            return
        if stamp == 0:
            self.pending_labels.append(label)
        else:
            label.utime = utime
            self.stamped_labels.append(label)

    def finish(self):
        content = self.content
        for _ in self.pending_labels:
            content.skip(f"{self.labels_topic} messages without a following scan",
                         "at the end of the bag")
        if not self.stamped_labels:
            return
        scan_utimes = {scan.utime for scan in content.scans}
        for label in self.stamped_labels:
            if label.utime in scan_utimes:
                content.labels.append(label)
            else:
                content.skip(f"{self.labels_topic} messages whose stamp is no scan's",
                             f"utime {label.utime}")
        content.labels.sort(key=lambda label: label.utime)


def _label(message, tree, content):
    """Label of a PoseArray: the positions in the laser frame (None: skipped, counted)."""
    frame = frame_name(message.header.frame_id)
    if len(message.poses) > MAX_LABELS_PER_SCAN:
        content.skip(f"label messages with more than {MAX_LABELS_PER_SCAN} positions",
                     f"{len(message.poses)} positions")
        return None
    points = np.array([[p.position.x, p.position.y, p.position.z] for p in message.poses],
                      dtype=np.float64).reshape(-1, 3)
    if not np.all(np.isfinite(points)):
        content.skip("label messages with non-finite positions", f"frame {frame}")
        return None
    if content.laser_frame and frame and frame != content.laser_frame:
        found = tree.lookup(content.laser_frame, frame)
        if found is None:
            content.skip(f"label messages in frame {frame}, not connected to the laser frame "
                         f"{content.laser_frame} by static transforms", f"frame {frame}")
            return None
        transform, _ = found
        points = points @ transform.rotation.T + transform.translation
    return Label(utime=0, x_m=points[:, 0].copy(), y_m=points[:, 1].copy())


def label_message(label, mount=None):
    """leg_labels_t of a Label; with a mount, the points turned into the robot's orientation."""
    from slammtt_msgs import leg_labels_t
    xs, ys = label.x_m, label.y_m
    if mount is not None:
        pairs = [mount.point_in_base_orientation(float(x), float(y)) for x, y in zip(xs, ys)]
        xs = [p[0] for p in pairs]
        ys = [p[1] for p in pairs]
    message = leg_labels_t()
    message.utime = int(label.utime)
    message.num_legs = len(xs)
    message.x_m = [float(x) for x in xs]
    message.y_m = [float(y) for y in ys]
    return message


