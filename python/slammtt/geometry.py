"""Planar rigid transforms (x_m, y_m, heading_rad), as tools/metrics/pose2.h defines them: a pose
maps a point of its own frame into its parent frame, p_parent = R(heading) p + t."""

import math
from typing import NamedTuple


class Pose2(NamedTuple):
    x_m: float = 0.0
    y_m: float = 0.0
    heading_rad: float = 0.0

    def compose(self, other):
        """self * other: first `other`, then self."""
        c, s = math.cos(self.heading_rad), math.sin(self.heading_rad)
        return Pose2(self.x_m + c * other.x_m - s * other.y_m,
                     self.y_m + s * other.x_m + c * other.y_m,
                     wrap_angle(self.heading_rad + other.heading_rad))

    def inverse(self):
        c, s = math.cos(self.heading_rad), math.sin(self.heading_rad)
        return Pose2(-c * self.x_m - s * self.y_m, s * self.x_m - c * self.y_m,
                     wrap_angle(-self.heading_rad))

    def apply(self, x_m, y_m):
        """The point (x_m, y_m) of this pose's frame in the parent frame."""
        c, s = math.cos(self.heading_rad), math.sin(self.heading_rad)
        return self.x_m + c * x_m - s * y_m, self.y_m + s * x_m + c * y_m

    def rotate_covariance(self, xx, xy, yy):
        """R C R^T of a 2x2 covariance given as (xx, xy, yy)."""
        c, s = math.cos(self.heading_rad), math.sin(self.heading_rad)
        rxx = c * c * xx - 2 * c * s * xy + s * s * yy
        rxy = c * s * (xx - yy) + (c * c - s * s) * xy
        ryy = s * s * xx + 2 * c * s * xy + c * c * yy
        return rxx, rxy, ryy


def wrap_angle(angle_rad):
    """To (-pi, pi], as WrapAngle (common/angle.h)."""
    wrapped = math.remainder(angle_rad, 2.0 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def anchor(truth, estimate):
    """The transform of slammtt-eval's anchoring (AnchorTransform, tools/metrics/pose2.h):
    truth * estimate^-1, which puts `estimate` exactly onto `truth`."""
    return truth.compose(estimate.inverse())


def yaw_quaternion(heading_rad):
    """(x, y, z, w) of the rotation by heading_rad about z."""
    return 0.0, 0.0, math.sin(heading_rad / 2.0), math.cos(heading_rad / 2.0)


def covariance_ellipse(xx, xy, yy, sigmas=2.0, points=32):
    """Closed polyline [(x, y), ...] (first point repeated at the end) of the `sigmas`-sigma
    ellipse of a 2x2 covariance around the origin; [] when it is not positive semi-definite or
    not finite."""
    if not all(math.isfinite(v) for v in (xx, xy, yy)):
        return []
    half_trace = 0.5 * (xx + yy)
    root = math.sqrt(max(0.0, 0.25 * (xx - yy) ** 2 + xy * xy))
    major, minor = half_trace + root, half_trace - root
    if minor < -1e-12 * max(1.0, abs(major)):
        return []
    angle = 0.5 * math.atan2(2.0 * xy, xx - yy)
    a, b = sigmas * math.sqrt(max(major, 0.0)), sigmas * math.sqrt(max(minor, 0.0))
    c, s = math.cos(angle), math.sin(angle)
    out = []
    for k in range(points + 1):
        t = 2.0 * math.pi * (k % points) / points
        u, v = a * math.cos(t), b * math.sin(t)
        out.append((c * u - s * v, s * u + c * v))
    return out
