"""A log of the stack, read once, as lists of checked messages per channel key.

Messages are checked as slammtt-eval checks them (docs/evaluation.md, "Bad messages are never
used"): a message of the wrong type for its channel, one holding a NaN or an infinity, or one
that repeats the utime of an earlier message of its channel is rejected and counted
(`LogData.rejected`, first reason in `LogData.notes`). Each channel's messages are then sorted by
their own utime (stable: a live recording may interleave them).
"""

import collections
import math

from slammtt.geometry import Pose2, anchor
from slammtt.lcmlog import LogReader

# The message type of each channel key.
EXPECTED_TYPES = {
    "odometry": "odometry_t", "laser_scan": "laser_scan_t", "features": "features_t",
    "pose": "pose_t", "smoothed_pose": "pose_t", "map": "map_t", "smoothed_map": "map_t",
    "tracks": "tracks_t", "smoothed_trajectory": "trajectory_t",
    "ground_truth": "ground_truth_t", "leg_labels": "leg_labels_t",
}


def _finite(*values):
    return all(math.isfinite(v) for v in values)


def _problem(key, m):
    """Why message m of channel key is unusable, or ''."""
    if key in ("pose", "smoothed_pose"):
        ok = _finite(m.x_m, m.y_m, m.heading_rad)
    elif key == "odometry":
        ok = _finite(m.x_m, m.y_m, m.heading_rad)
    elif key == "ground_truth":
        ok = _finite(m.robot_x_m, m.robot_y_m, m.robot_heading_rad) and all(
            _finite(o.x_m, o.y_m, o.vx_mps, o.vy_mps, o.radius_m) for o in m.objects)
        if ok and len({o.id for o in m.objects}) != len(m.objects):
            return "duplicate object ids"
    elif key == "tracks":
        ok = all(_finite(t.x_m, t.y_m, t.vx_mps, t.vy_mps) for t in m.tracks)
    elif key in ("map", "smoothed_map"):
        ok = all(_finite(l.x_m, l.y_m) for l in m.landmarks)
    elif key == "smoothed_trajectory":
        ok = _finite(*m.x_m, *m.y_m, *m.heading_rad)
        if ok and any(u < 0 for u in m.pose_utime):
            return "a negative keyframe utime"
        if ok and any(b <= a for a, b in zip(m.pose_utime, m.pose_utime[1:])):
            return "keyframe utimes not increasing"
    else:
        return ""
    return "" if ok else "a NaN or infinite value"


class LogData:
    """{channel key: [message, ...]} of a log, checked and sorted by utime.

    `channels` maps channel keys to names (slammtt.stackconfig). Channels with other names are
    counted in `other_channels` and otherwise ignored.
    """

    def __init__(self, path, channels):
        self.path = str(path)
        self.channels = dict(channels)
        by_name = {name: key for key, name in self.channels.items()}
        self.messages = {key: [] for key in self.channels}
        self.rejected = collections.Counter()
        self.notes = []
        self.other_channels = collections.Counter()
        reader = LogReader(path)
        seen_utimes = collections.defaultdict(set)
        for channel, _, message in reader:
            key = by_name.get(channel)
            if key is None:
                self.other_channels[channel] += 1
                continue
            expected = EXPECTED_TYPES.get(key)
            why = ""
            if expected and type(message).__name__ != expected:
                why = f"a {type(message).__name__}, not a {expected}"
            elif expected:
                why = _problem(key, message)
                if not why and message.utime in seen_utimes[key]:
                    why = f"utime {message.utime} repeated"
            if why:
                if not self.rejected[channel]:
                    self.notes.append(f"{channel}: rejected a message ({why})")
                self.rejected[channel] += 1
                continue
            if expected:
                seen_utimes[key].add(message.utime)
            self.messages[key].append(message)
        for key, messages in self.messages.items():
            if messages and hasattr(messages[0], "utime"):
                messages.sort(key=lambda m: m.utime)
        self.undecodable = dict(reader.undecodable)
        self.first_undecodable = reader.first_undecodable
        self.damage = reader.damage

    def __getitem__(self, key):
        return self.messages.get(key, [])

    def name(self, key):
        return self.channels[key]

    def truth_anchor(self):
        """(utime, Pose2) of slammtt-eval's anchoring: the transform truth * estimate^-1 at the
        first GROUND_TRUTH scan that has a POSE of exactly the same utime; None without one."""
        poses = {m.utime: m for m in self["pose"]}
        for truth in self["ground_truth"]:
            estimate = poses.get(truth.utime)
            if estimate is not None:
                return truth.utime, anchor(
                    Pose2(truth.robot_x_m, truth.robot_y_m, truth.robot_heading_rad),
                    Pose2(estimate.x_m, estimate.y_m, estimate.heading_rad))
        return None
