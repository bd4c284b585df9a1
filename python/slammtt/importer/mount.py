"""Where the laser sits on the robot: from a bag's static transforms, or from options.

The estimator models the laser at (sensor_forward_m, sensor_left_m) in the robot frame (paper
eqs. 10-11: a, b), turned by sensor_yaw_deg. A mount therefore has a forward and left offset, a
yaw (written into the configuration snippet as sensor_yaw_deg), and two facts about the laser's
axis: upside down (its z axis points down: beam angles turn the other way in the robot
frame) and tilt (angle between its z axis and the robot's vertical; the scan is treated as
planar).

The transform base_frame -> laser_frame is composed along the tf tree of the bag:
/tf_static first; a transform on /tf is taken as static when every sample of it is the same
(static_transform_publisher in ROS 1 publishes on /tf); one that changes is never a mount.
Frame names are compared without a leading '/' (tf2's convention).
"""

import collections
import dataclasses
import math

import numpy as np

from slammtt.importer.geometry import Transform, wrap_angle, yaw_of_rotation

# Tilt beyond this is reported (a 2D laser's scan is treated as lying in the robot's plane).
TILT_WARNING_RAD = math.radians(1.0)
YAW_ZERO_RAD = 1e-6


def frame_name(frame_id):
    return frame_id[1:] if frame_id.startswith("/") else frame_id


@dataclasses.dataclass
class Mount:
    forward_m: float = 0.0
    left_m: float = 0.0
    yaw_rad: float = 0.0
    upside_down: bool = False
    tilt_rad: float = 0.0
    source: str = "default (no transform, no option): the laser on the axle centre"

    @staticmethod
    def from_transform(transform, source):
        """The mount of laser frame `child` given parent(base) <- child."""
        r = transform.rotation
        up = r[:, 2]
        upside_down = bool(up[2] < 0.0)
        tilt = math.acos(min(1.0, abs(float(up[2]))))
        # Beam at angle a in the laser frame: direction R (cos a, sin a, 0); its heading in the
        # robot frame is yaw + a (upright) or yaw - a (upside down), yaw from the x axis.
        yaw = yaw_of_rotation(r)
        t = transform.translation
        return Mount(forward_m=float(t[0]), left_m=float(t[1]), yaw_rad=wrap_angle(yaw),
                     upside_down=upside_down, tilt_rad=tilt, source=source)

    def beam_angles_in_base(self, angles_rad):
        """Beam angles of the laser frame turned into the robot's orientation."""
        a = np.asarray(angles_rad, dtype=np.float64)
        return self.yaw_rad + (-a if self.upside_down else a)

    def point_in_base_orientation(self, x_m, y_m):
        """A point of the laser frame in axes parallel to the robot's, origin at the laser."""
        if self.upside_down:
            y_m = -y_m
        c, s = math.cos(self.yaw_rad), math.sin(self.yaw_rad)
        return c * x_m - s * y_m, s * x_m + c * y_m

    def describe(self):
        text = (f"forward {self.forward_m:.4f} m, left {self.left_m:.4f} m, "
                f"yaw {math.degrees(self.yaw_rad):.2f} deg")
        if self.upside_down:
            text += ", upside down"
        if self.tilt_rad > TILT_WARNING_RAD:
            text += f", tilted {math.degrees(self.tilt_rad):.2f} deg"
        return f"{text} ({self.source})"

    def warnings(self, rotated_to_base):
        """Lines the user must read about this mount."""
        lines = []
        if not rotated_to_base and self.upside_down:
            lines.append("the laser is upside down: its beams turn clockwise in the robot "
                         "frame; --rotate-to-base writes them in the robot's orientation")
        if self.tilt_rad > TILT_WARNING_RAD:
            lines.append(f"the laser is tilted by {math.degrees(self.tilt_rad):.2f} deg; the "
                         "scan is treated as planar")
        return lines

    def yaml(self, header_lines, rotated_to_base):
        """A stack configuration holding this mount: `slammtt-replay LOG --config FILE` takes
        it as it is, and its estimator section can be pasted into any configuration."""
        lines = [f"# {line}" for line in header_lines]
        lines += [
            "estimator:",
            f"  sensor_forward_m: {_number(self.forward_m)}",
            f"  sensor_left_m: {_number(self.left_m)}",
        ]
        if rotated_to_base:
            lines.append("  sensor_yaw_deg: 0.0")
            lines.append(f"# sensor yaw {_number(math.degrees(self.yaw_rad))} deg"
                         f"{' and upside down' if self.upside_down else ''}: already applied "
                         "to the beams (--rotate-to-base)")
        else:
            lines.append(f"  sensor_yaw_deg: {_number(math.degrees(self.yaw_rad))}")
            if self.upside_down:
                lines.append("# upside down: the beams turn clockwise; import with "
                             "--rotate-to-base")
        return "\n".join(lines) + "\n"


def _number(value):
    text = f"{value:.6f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


class TransformTree:
    """Static transforms of a bag, by (parent, child)."""

    def __init__(self):
        self._static = {}                             # (parent, child) -> Transform
        self._dynamic = collections.defaultdict(list)  # (parent, child) -> [Transform]
        self.conflicts = []                           # one line per disagreeing /tf_static
        self.rejected = 0                             # transforms that are not rigid motions

    def add(self, transform_stamped, static):
        parent = frame_name(transform_stamped.header.frame_id)
        child = frame_name(transform_stamped.child_frame_id)
        try:
            t = Transform.from_ros(transform_stamped.transform.translation,
                                   transform_stamped.transform.rotation)
        except ValueError:
            self.rejected += 1
            return
        key = (parent, child)
        if static:
            old = self._static.get(key)
            if old is not None and not old.close_to(t):
                self.conflicts.append(f"/tf_static {parent} -> {child} changes; the last "
                                      "one is used")
            self._static[key] = t
        else:
            samples = self._dynamic[key]   # the distinct values seen, two at most
            if not samples or (len(samples) == 1 and not samples[0].close_to(t)):
                samples.append(t)

    def frames(self):
        names = set()
        for parent, child in list(self._static) + list(self._dynamic):
            names.update((parent, child))
        return names

    def _edges(self):
        """(parent, child) -> (Transform, source) of everything usable as static."""
        edges = {key: (t, "/tf_static") for key, t in self._static.items()}
        for key, samples in self._dynamic.items():
            if key not in edges and len(samples) == 1:
                edges[key] = (samples[0], "/tf, constant")
        return edges

    def changing(self):
        return sorted(f"{p} -> {c}" for (p, c), s in self._dynamic.items() if len(s) > 1)

    def lookup(self, base, laser):
        """(Transform base <- laser, source) along the tree, or None when they are not
        connected by static transforms."""
        if base == laser:
            return Transform.identity(), "the same frame"
        neighbours = collections.defaultdict(list)
        for (parent, child), (t, source) in sorted(self._edges().items()):
            neighbours[parent].append((child, t, source))
            neighbours[child].append((parent, t.inverse(), source))
        # Breadth-first from the base: the result is parent(base) <- frame.
        found = {base: (Transform.identity(), [])}
        queue = collections.deque([base])
        while queue:
            frame = queue.popleft()
            to_frame, sources = found[frame]
            for other, t, source in neighbours[frame]:
                if other in found:
                    continue
                found[other] = (to_frame.then(t), sources + [source])
                queue.append(other)
        if laser not in found:
            return None
        transform, sources = found[laser]
        return transform, " and ".join(sorted(set(sources)))
