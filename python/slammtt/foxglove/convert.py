"""The stack's LCM messages as Foxglove messages (docs/export.md, "Foxglove schemas"), for the
MCAP export and the live WebSocket view alike.

Frames (x forward, y left, z up; every message of the stack is planar, z = 0):

  world --(anchor)--> map --(POSE)--> base_link --(mount)--> laser
                       \\--(anchor)--> odom

- map -> base_link: every POSE (without POSE in the log: odom -> base_link from ODOMETRY);
- base_link -> laser: the mount of the stack configuration (estimator.sensor_forward_m,
  sensor_left_m; the laser faces forward), or, when it gives none (mount_from_log), the mount
  of the stream's LASER_GEOMETRY, yaw included (docs/estimator.md, "Laser geometry");
- world -> map: slammtt-eval's anchoring, truth * estimate^-1 at the first GROUND_TRUTH scan
  with a POSE of the same utime, so that the truth is drawn where slammtt-eval compares it;
- map -> odom: estimate * odometry^-1 at the first POSE, with the last ODOMETRY at or before it
  (the odometry drawn from where the estimate started, its drift visible).
Constant transforms are sent again every `republish_s` seconds of message time, so a viewer
that joins late or seeks finds them.

Timestamps: a Foxglove message's timestamp and log time are the LCM message's utime (the moment
it describes), in nanoseconds.

Bad input: a message whose values are not finite is skipped and counted in `skipped` (by
channel), never converted half; an unknown channel is ignored.
"""

import math
from typing import NamedTuple

import numpy as np
from foxglove import channels as fc
from foxglove import messages as fm

from slammtt.geometry import Pose2, anchor, covariance_ellipse, yaw_quaternion

MAP, ODOM, WORLD, BASE, LASER = "map", "odom", "world", "base_link", "laser"

# topic -> (Foxglove channel class, what it shows)
TOPICS = {
    "/tf": (fc.FrameTransformsChannel, "frame transforms (FrameTransforms)"),
    "/laser_scan": (fc.LaserScanChannel, "LASER_SCAN as a LaserScan, frame laser"),
    "/laser_scan/points": (fc.PointCloudChannel,
                           "LASER_SCAN's valid beams as points (x, y, z, intensity), frame laser"),
    "/pose": (fc.PoseInFrameChannel, "POSE, frame map"),
    "/smoothed_pose": (fc.PoseInFrameChannel, "SMOOTHED_POSE, frame map"),
    "/odometry": (fc.PoseInFrameChannel, "ODOMETRY, frame odom"),
    "/ground_truth/pose": (fc.PoseInFrameChannel, "GROUND_TRUTH robot pose, frame world"),
    "/map": (fc.SceneUpdateChannel,
             "MAP: landmarks with 2-sigma ellipses and ids, line landmarks, frame map"),
    "/smoothed_map": (fc.SceneUpdateChannel,
                      "SMOOTHED_MAP: the smoother's landmarks with 2-sigma ellipses and ids, "
                      "frame map"),
    "/tracks": (fc.SceneUpdateChannel,
                "TRACKS: tracks with 2-sigma ellipses, velocity arrows, ids, frame map"),
    "/features": (fc.SceneUpdateChannel,
                  "FEATURES: point features, line features, people, frame laser"),
    "/ground_truth/objects": (fc.SceneUpdateChannel,
                              "GROUND_TRUTH objects (people, legs, posts, discs), frame world"),
    "/ground_truth/walls": (fc.SceneUpdateChannel,
                            "GROUND_TRUTH walls and furniture sides, frame world"),
    "/leg_labels": (fc.SceneUpdateChannel, "LEG_LABELS: labelled legs, frame laser"),
}

# Track colours by identity: the 12 of slammtt-eval's pictures (tools/plots).
PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
           "#17becf", "#bcbd22", "#7f7f7f", "#393b79", "#637939"]
TRACK_CLASS = {0: "static", 1: "moving", 2: "undecided"}
TRUTH_KIND = {0: "object", 3: "post", 4: "disc", 5: "person", 6: "leg", 2: "furniture"}


class Output(NamedTuple):
    topic: str
    message: object
    log_time_ns: int


def _color(hex_or_rgb, alpha=1.0):
    if isinstance(hex_or_rgb, str):
        r, g, b = (int(hex_or_rgb[i:i + 2], 16) / 255.0 for i in (1, 3, 5))
    else:
        r, g, b = hex_or_rgb
    return fm.Color(r=r, g=g, b=b, a=alpha)


GREY = (0.55, 0.55, 0.6)
STATIC_COLOR = (0.3, 0.4, 0.8)
UNDECIDED_COLOR = (0.95, 0.7, 0.1)
SMOOTHED_COLOR = (0.2, 0.65, 0.3)
TRUTH_COLOR = (0.1, 0.6, 0.1)
LINE_COLOR = (0.9, 0.2, 0.6)
PERSON_COLOR = (0.85, 0.1, 0.1)


def timestamp(utime):
    seconds, micros = divmod(int(utime), 1000000)
    return fm.Timestamp(sec=seconds, nsec=micros * 1000)


def _pose(x_m=0.0, y_m=0.0, heading_rad=0.0, z_m=0.0):
    qx, qy, qz, qw = yaw_quaternion(heading_rad)
    return fm.Pose(position=fm.Vector3(x=float(x_m), y=float(y_m), z=float(z_m)),
                   orientation=fm.Quaternion(x=qx, y=qy, z=qz, w=qw))


def _transform(utime, parent, child, pose):
    qx, qy, qz, qw = yaw_quaternion(pose.heading_rad)
    return fm.FrameTransform(timestamp=timestamp(utime), parent_frame_id=parent,
                             child_frame_id=child,
                             translation=fm.Vector3(x=pose.x_m, y=pose.y_m, z=0.0),
                             rotation=fm.Quaternion(x=qx, y=qy, z=qz, w=qw))


def _ellipse(x_m, y_m, xx, xy, yy, color, z_m=0.0):
    points = covariance_ellipse(xx, xy, yy)
    if not points:
        return []
    return [fm.LinePrimitive(type=fm.LinePrimitiveLineType.LineStrip, pose=_pose(),
                             thickness=0.02, color=color,
                             points=[fm.Point3(x=x_m + u, y=y_m + v, z=z_m) for u, v in points])]


def _text(x_m, y_m, text, color, z_m=0.4):
    return fm.TextPrimitive(pose=_pose(x_m, y_m, 0.0, z_m), billboard=True, font_size=14.0,
                            scale_invariant=True, color=color, text=text)


def _sphere(x_m, y_m, diameter_m, color, z_m=0.0):
    return fm.SpherePrimitive(pose=_pose(x_m, y_m, 0.0, z_m),
                              size=fm.Vector3(x=diameter_m, y=diameter_m, z=diameter_m),
                              color=color)


def _metadata(**values):
    return [fm.KeyValuePair(key=k, value=str(v)) for k, v in values.items()]


def _finite(*values):
    return all(math.isfinite(v) for v in values)


def laser_scan_ranges(angle_rad, range_m, valid, intensity):
    """The beams of a laser_scan_t on the evenly spaced angles a Foxglove LaserScan assumes:
    (start_angle, end_angle, ranges, intensities). Angles are taken counter-clockwise from the
    first beam (in [a0, a0 + 2 pi)); with n beams, slot i is at a0 + i (span / (n - 1)), span
    the largest such angle; each beam goes to its nearest slot, the nearer valid range winning
    a slot two beams share. Evenly spaced beams (the synthetic laser, a bag's LaserScan) map
    one to one, unchanged; an RPLIDAR's uneven beams move by at most half a slot (the point
    cloud topic has them exactly). Invalid beams and empty slots are NaN (nothing drawn)."""
    n = len(range_m)
    if n == 0:
        return 0.0, 0.0, [], []
    angles = np.asarray(angle_rad, dtype=np.float64)
    ranges = np.where(np.asarray(valid, dtype=bool), np.asarray(range_m, dtype=np.float64),
                      np.nan)
    start = float(angles[0])
    offsets = np.mod(angles - start, 2.0 * math.pi)
    span = float(offsets.max())
    if n == 1 or span == 0.0:
        return start, start, [float(ranges[0])], [float(intensity[0])]
    step = span / (n - 1)
    slots = np.rint(offsets / step).astype(np.int64)
    out_ranges = np.full(n, np.nan)
    out_intensity = np.zeros(n)
    for i in np.argsort(np.where(np.isnan(ranges), np.inf, ranges), kind="stable")[::-1]:
        # Farthest first: a nearer valid beam in the same slot overwrites it.
        slot = slots[i]
        if np.isnan(ranges[i]) and not np.isnan(out_ranges[slot]):
            continue
        out_ranges[slot] = ranges[i]
        out_intensity[slot] = intensity[i]
    return start, start + span, out_ranges.tolist(), out_intensity.tolist()


class Converter:
    """Converts the messages of one stream (a log in order, or a live bus) to Output lists.

    `channels`: {channel key: channel name} (slammtt.stackconfig); `mount`: (forward_m, left_m)
    of the laser on the robot; `mount_from_log`: a LASER_GEOMETRY of the stream replaces it.
    """

    def __init__(self, channels, mount=(0.0, 0.0), republish_s=1.0, mount_from_log=False):
        self.key_of = {name: key for key, name in channels.items()}
        self.mount = Pose2(float(mount[0]), float(mount[1]), 0.0)
        self.mount_from_log = mount_from_log
        self.republish_us = int(republish_s * 1e6)
        self.skipped = {}
        self.converted = {}
        self._constant = {}          # child frame -> (parent, Pose2)
        self._last_constant_us = None
        self._truth_by_utime = {}
        self._pose_by_utime = {}
        self._anchored = False
        self._last_odometry = None
        self._have_pose = False
        self._track_ids = set()
        self._landmark_ids = set()
        self._smoothed_ids = set()
        self._truth_ids = set()
        self._walls = None
        self._last_walls_us = None
        self._constant[LASER] = (BASE, self.mount)

    def convert(self, channel, message):
        key = self.key_of.get(channel)
        handler = getattr(self, "_" + key, None) if key else None
        if handler is None or not hasattr(message, "utime"):
            return []
        try:
            outputs = handler(message)
        except _Skip:
            self.skipped[channel] = self.skipped.get(channel, 0) + 1
            return []
        outputs = self._constants_due(message.utime) + outputs
        self.converted[channel] = self.converted.get(channel, 0) + 1
        return outputs

    # Constant transforms.
    def _constants_due(self, utime):
        if self._last_constant_us is not None and \
                0 <= utime - self._last_constant_us < self.republish_us:
            return []
        return self._send_constants(utime)

    def _send_constants(self, utime):
        self._last_constant_us = utime
        transforms = [_transform(utime, parent, child, pose)
                      for child, (parent, pose) in sorted(self._constant.items())]
        return [Output("/tf", fm.FrameTransforms(transforms=transforms), utime * 1000)]

    def _add_constant(self, utime, parent, child, pose):
        self._constant[child] = (parent, pose)
        return self._send_constants(utime)

    def _laser_geometry(self, m):
        if not self.mount_from_log:
            return []
        if not _finite(m.mount_forward_m, m.mount_left_m, m.mount_yaw_rad):
            raise _Skip()
        mount = Pose2(m.mount_forward_m, m.mount_left_m, m.mount_yaw_rad)
        if mount == self.mount:
            return []
        self.mount = mount
        return self._add_constant(m.utime, BASE, LASER, mount)

    def _anchor(self, utime, truth, estimate):
        self._anchored = True
        self._truth_by_utime.clear()
        self._pose_by_utime.clear()
        return self._add_constant(utime, WORLD, MAP, anchor(truth, estimate))

    # Robot poses.
    def _pose(self, m):
        if not _finite(m.x_m, m.y_m, m.heading_rad):
            raise _Skip()
        out = []
        estimate = Pose2(m.x_m, m.y_m, m.heading_rad)
        if not self._have_pose:
            self._have_pose = True
            if self._last_odometry is not None:
                out += self._add_constant(m.utime, MAP, ODOM,
                                          estimate.compose(self._last_odometry.inverse()))
        if not self._anchored:
            truth = self._truth_by_utime.get(m.utime)
            if truth is not None:
                out += self._anchor(m.utime, truth, estimate)
            else:
                _remember(self._pose_by_utime, m.utime, estimate)
        out.append(Output("/tf", fm.FrameTransforms(transforms=[
            _transform(m.utime, MAP, BASE, estimate)]), m.utime * 1000))
        out.append(Output("/pose", fm.PoseInFrame(timestamp=timestamp(m.utime), frame_id=MAP,
                                                  pose=_pose(m.x_m, m.y_m, m.heading_rad)),
                          m.utime * 1000))
        return out

    def _smoothed_pose(self, m):
        if not _finite(m.x_m, m.y_m, m.heading_rad):
            raise _Skip()
        return [Output("/smoothed_pose", fm.PoseInFrame(
            timestamp=timestamp(m.utime), frame_id=MAP,
            pose=_pose(m.x_m, m.y_m, m.heading_rad)), m.utime * 1000)]

    def _odometry(self, m):
        if not _finite(m.x_m, m.y_m, m.heading_rad):
            raise _Skip()
        self._last_odometry = Pose2(m.x_m, m.y_m, m.heading_rad)
        out = [Output("/odometry", fm.PoseInFrame(timestamp=timestamp(m.utime), frame_id=ODOM,
                                                  pose=_pose(m.x_m, m.y_m, m.heading_rad)),
                      m.utime * 1000)]
        if not self._have_pose:
            out.append(Output("/tf", fm.FrameTransforms(transforms=[
                _transform(m.utime, ODOM, BASE, self._last_odometry)]), m.utime * 1000))
        return out

    # Laser.
    def _laser_scan(self, m):
        angles = np.asarray(m.angle_rad, dtype=np.float64)
        ranges = np.asarray(m.range_m, dtype=np.float64)
        valid = np.asarray(m.valid, dtype=bool)
        if not np.all(np.isfinite(angles)):
            raise _Skip()
        intensity = np.nan_to_num(np.asarray(m.intensity, dtype=np.float64))
        valid &= np.isfinite(ranges)
        start, end, scan_ranges, scan_intensity = laser_scan_ranges(angles, ranges, valid,
                                                                    intensity)
        scan = fm.LaserScan(timestamp=timestamp(m.utime), frame_id=LASER, pose=_pose(),
                            start_angle=start, end_angle=end, ranges=scan_ranges,
                            intensities=scan_intensity)
        points = np.zeros((int(valid.sum()), 4), dtype="<f4")
        points[:, 0] = ranges[valid] * np.cos(angles[valid])
        points[:, 1] = ranges[valid] * np.sin(angles[valid])
        points[:, 3] = intensity[valid]
        fields = [fm.PackedElementField(name=name, offset=4 * i,
                                        type=fm.PackedElementFieldNumericType.Float32)
                  for i, name in enumerate(("x", "y", "z", "intensity"))]
        cloud = fm.PointCloud(timestamp=timestamp(m.utime), frame_id=LASER, pose=_pose(),
                              point_stride=16, fields=fields, data=points.tobytes())
        return [Output("/laser_scan", scan, m.utime * 1000),
                Output("/laser_scan/points", cloud, m.utime * 1000)]

    def _features(self, m):
        stamp = timestamp(m.utime)
        points, people, lines = [], [], []
        for f in m.features:
            if not _finite(f.range_m, f.bearing_rad, f.width_m):
                raise _Skip()
            x, y = f.range_m * math.cos(f.bearing_rad), f.range_m * math.sin(f.bearing_rad)
            leg_like = f.leg_likeness >= 0.5
            points.append(_sphere(x, y, max(f.width_m, 0.05),
                                  _color((0.9, 0.5, 0.1) if leg_like else GREY, 0.8)))
        for p in m.people:
            if not _finite(p.range_m, p.bearing_rad):
                raise _Skip()
            x, y = p.range_m * math.cos(p.bearing_rad), p.range_m * math.sin(p.bearing_rad)
            people.append(fm.CylinderPrimitive(
                pose=_pose(x, y, 0.0, 0.5), size=fm.Vector3(x=0.5, y=0.5, z=1.0),
                bottom_scale=1.0, top_scale=1.0, color=_color(PERSON_COLOR, 0.35)))
        for line in m.lines:
            ends = (line.first_x_m, line.first_y_m, line.last_x_m, line.last_y_m)
            if not _finite(*ends):
                raise _Skip()
            lines.append(fm.LinePrimitive(
                type=fm.LinePrimitiveLineType.LineList, pose=_pose(), thickness=0.04,
                color=_color(LINE_COLOR),
                points=[fm.Point3(x=ends[0], y=ends[1]), fm.Point3(x=ends[2], y=ends[3])]))
        entities = [
            fm.SceneEntity(timestamp=stamp, frame_id=LASER, id="point_features", spheres=points,
                           metadata=_metadata(count=len(points))),
            fm.SceneEntity(timestamp=stamp, frame_id=LASER, id="line_features", lines=lines,
                           metadata=_metadata(count=len(lines))),
            fm.SceneEntity(timestamp=stamp, frame_id=LASER, id="people", cylinders=people,
                           metadata=_metadata(count=len(people))),
        ]
        return [Output("/features", fm.SceneUpdate(entities=entities), m.utime * 1000)]

    def _leg_labels(self, m):
        if not _finite(*m.x_m, *m.y_m):
            raise _Skip()
        spheres = [_sphere(x, y, 0.15, _color(TRUTH_COLOR, 0.8)) for x, y in zip(m.x_m, m.y_m)]
        return [Output("/leg_labels", fm.SceneUpdate(entities=[fm.SceneEntity(
            timestamp=timestamp(m.utime), frame_id=LASER, id="leg_labels", spheres=spheres,
            metadata=_metadata(count=len(spheres)))]), m.utime * 1000)]

    # Estimator state.
    @staticmethod
    def _deletions(stamp, previous, current):
        return [fm.SceneEntityDeletion(timestamp=stamp,
                                       type=fm.SceneEntityDeletionType.MatchingId, id=i)
                for i in sorted(previous - current)]

    def _map_update(self, m, previous_ids, point_rgb):
        """A map_t as a SceneUpdate (landmarks with ellipses and ids, line landmarks) and the
        ids of its entities, deleting those of `previous_ids` that are gone."""
        stamp = timestamp(m.utime)
        entities, ids = [], set()
        for l in m.landmarks:
            c = list(l.covariance)
            if not _finite(l.x_m, l.y_m):
                raise _Skip()
            entity_id = f"landmark/{l.id}"
            ids.add(entity_id)
            color = _color(point_rgb)
            entities.append(fm.SceneEntity(
                timestamp=stamp, frame_id=MAP, id=entity_id,
                spheres=[_sphere(l.x_m, l.y_m, 0.15, color)],
                lines=_ellipse(l.x_m, l.y_m, c[0], c[1], c[3], color),
                texts=[_text(l.x_m, l.y_m, str(l.id), color)],
                metadata=_metadata(id=l.id, x_m=l.x_m, y_m=l.y_m)))
        for l in m.lines:
            ends = (l.from_x_m, l.from_y_m, l.to_x_m, l.to_y_m)
            if not _finite(l.rho_m, l.alpha_rad, *ends):
                raise _Skip()
            entity_id = f"line/{l.id}"
            ids.add(entity_id)
            color = _color(LINE_COLOR)
            entities.append(fm.SceneEntity(
                timestamp=stamp, frame_id=MAP, id=entity_id,
                lines=[fm.LinePrimitive(
                    type=fm.LinePrimitiveLineType.LineList, pose=_pose(), thickness=0.06,
                    color=color,
                    points=[fm.Point3(x=ends[0], y=ends[1]), fm.Point3(x=ends[2], y=ends[3])])],
                texts=[_text((ends[0] + ends[2]) / 2, (ends[1] + ends[3]) / 2, str(l.id),
                             color)],
                metadata=_metadata(id=l.id, rho_m=l.rho_m, alpha_rad=l.alpha_rad,
                                   hits=l.hits)))
        deletions = self._deletions(stamp, previous_ids, ids)
        return fm.SceneUpdate(deletions=deletions, entities=entities), ids

    def _map(self, m):
        update, self._landmark_ids = self._map_update(m, self._landmark_ids, STATIC_COLOR)
        return [Output("/map", update, m.utime * 1000)]

    def _smoothed_map(self, m):
        update, self._smoothed_ids = self._map_update(m, self._smoothed_ids, SMOOTHED_COLOR)
        return [Output("/smoothed_map", update, m.utime * 1000)]

    def _tracks(self, m):
        stamp = timestamp(m.utime)
        entities, ids = [], set()
        for t in m.tracks:
            if not _finite(t.x_m, t.y_m, t.vx_mps, t.vy_mps):
                raise _Skip()
            c = list(t.covariance)
            entity_id = f"track/{t.id}"
            ids.add(entity_id)
            name = TRACK_CLASS.get(t.object_class, str(t.object_class))
            rgb = (PALETTE[t.id % len(PALETTE)] if t.object_class == 1 else
                   STATIC_COLOR if t.object_class == 0 else UNDECIDED_COLOR)
            color = _color(rgb, 1.0 if t.confirmed else 0.35)
            arrows = []
            speed = math.hypot(t.vx_mps, t.vy_mps)
            if speed > 0.05:
                arrows.append(fm.ArrowPrimitive(
                    pose=_pose(t.x_m, t.y_m, math.atan2(t.vy_mps, t.vx_mps), 0.1),
                    shaft_length=speed, shaft_diameter=0.03, head_length=0.1,
                    head_diameter=0.08, color=color))
            entities.append(fm.SceneEntity(
                timestamp=stamp, frame_id=MAP, id=entity_id,
                spheres=[_sphere(t.x_m, t.y_m, 0.3, color)],
                lines=_ellipse(t.x_m, t.y_m, c[0], c[1], c[5], color),
                arrows=arrows,
                texts=[_text(t.x_m, t.y_m, f"{t.id} {name}", color)],
                metadata=_metadata(id=t.id, object_class=name, confirmed=bool(t.confirmed),
                                   hits=t.hits, vx_mps=t.vx_mps, vy_mps=t.vy_mps)))
        deletions = self._deletions(stamp, self._track_ids, ids)
        self._track_ids = ids
        return [Output("/tracks", fm.SceneUpdate(deletions=deletions, entities=entities),
                       m.utime * 1000)]

    # Ground truth.
    def _ground_truth(self, m):
        if not _finite(m.robot_x_m, m.robot_y_m, m.robot_heading_rad):
            raise _Skip()
        truth = Pose2(m.robot_x_m, m.robot_y_m, m.robot_heading_rad)
        out = []
        if not self._anchored:
            estimate = self._pose_by_utime.get(m.utime)
            if estimate is not None:
                out += self._anchor(m.utime, truth, estimate)
            else:
                _remember(self._truth_by_utime, m.utime, truth)
        stamp = timestamp(m.utime)
        out += [Output("/ground_truth/pose", fm.PoseInFrame(
            timestamp=stamp, frame_id=WORLD,
            pose=_pose(m.robot_x_m, m.robot_y_m, m.robot_heading_rad)), m.utime * 1000)]
        entities, ids = [], set()
        for o in m.objects:
            if not _finite(o.x_m, o.y_m, o.radius_m):
                raise _Skip()
            entity_id = f"truth/{o.id}"
            ids.add(entity_id)
            kind = TRUTH_KIND.get(o.kind, "object")
            moving = o.object_class == 1
            alpha = 0.9 if o.visible else 0.3
            color = _color(PERSON_COLOR if kind == "person" else
                           TRUTH_COLOR if moving else GREY, alpha)
            if kind == "person":
                cylinders = [fm.CylinderPrimitive(
                    pose=_pose(o.x_m, o.y_m, 0.0, 0.85),
                    size=fm.Vector3(x=2 * o.radius_m, y=2 * o.radius_m, z=1.7),
                    bottom_scale=1.0, top_scale=1.0, color=_color(PERSON_COLOR, 0.2))]
            else:
                height = 0.8 if kind == "leg" else 1.0
                cylinders = [fm.CylinderPrimitive(
                    pose=_pose(o.x_m, o.y_m, 0.0, height / 2),
                    size=fm.Vector3(x=max(2 * o.radius_m, 0.02), y=max(2 * o.radius_m, 0.02),
                                    z=height),
                    bottom_scale=1.0, top_scale=1.0, color=color)]
            texts = [] if kind == "leg" else [_text(o.x_m, o.y_m, f"{o.id}", color, 1.9)]
            entities.append(fm.SceneEntity(
                timestamp=stamp, frame_id=WORLD, id=entity_id, cylinders=cylinders, texts=texts,
                metadata=_metadata(id=o.id, kind=kind, moving=moving, visible=bool(o.visible),
                                   beams_on_object=o.beams_on_object)))
        deletions = self._deletions(stamp, self._truth_ids, ids)
        self._truth_ids = ids
        out.append(Output("/ground_truth/objects",
                          fm.SceneUpdate(deletions=deletions, entities=entities),
                          m.utime * 1000))
        walls = tuple((s.id, s.kind, s.x0_m, s.y0_m, s.x1_m, s.y1_m) for s in m.segments)
        if walls != self._walls or self._last_walls_us is None or \
                not 0 <= m.utime - self._last_walls_us < self.republish_us:
            self._walls, self._last_walls_us = walls, m.utime
            points = []
            for _, _, x0, y0, x1, y1 in walls:
                if _finite(x0, y0, x1, y1):
                    points += [fm.Point3(x=x0, y=y0), fm.Point3(x=x1, y=y1)]
            out.append(Output("/ground_truth/walls", fm.SceneUpdate(entities=[fm.SceneEntity(
                timestamp=stamp, frame_id=WORLD, id="walls", lines=[fm.LinePrimitive(
                    type=fm.LinePrimitiveLineType.LineList, pose=_pose(), thickness=0.05,
                    color=_color((0.2, 0.2, 0.2)), points=points)] if points else [],
                metadata=_metadata(segments=len(walls)))]), m.utime * 1000))
        return out


def _remember(by_utime, utime, pose):
    """Keeps the last 64 poses by utime: the pose of the same scan on the other channel comes
    within a few scans, or never."""
    by_utime[utime] = pose
    while len(by_utime) > 64:
        del by_utime[min(by_utime)]


class _Skip(Exception):
    """The message holds a value that cannot be drawn."""


class ChannelSet:
    """The Foxglove channels of a context (an MCAP file's or a WebSocket server's). Lazy (an
    MCAP file): each is made when its first message is logged, so that only topics with data
    are listed. Eager (a live server): every topic of TOPICS is made at once, so that a viewer
    sees every channel advertised before the first message arrives."""

    def __init__(self, context, eager=False):
        self.context = context
        self.channels = {}
        self.counts = {}
        if eager:
            for topic, (channel_class, _) in TOPICS.items():
                self.channels[topic] = channel_class(topic, context=context)

    def log(self, output):
        channel = self.channels.get(output.topic)
        if channel is None:
            channel = TOPICS[output.topic][0](output.topic, context=self.context)
            self.channels[output.topic] = channel
        channel.log(output.message, log_time=output.log_time_ns)
        self.counts[output.topic] = self.counts.get(output.topic, 0) + 1
