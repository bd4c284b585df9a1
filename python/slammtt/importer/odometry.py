"""Wheel odometry -> odometry_t: from nav_msgs/Odometry, and from wheel encoder ticks.

nav_msgs/Odometry: the pose of child_frame_id (the robot) in header.frame_id (the odometry
frame); its twist is in child_frame_id. Mapped: x_m, y_m = pose.pose.position.x, .y;
heading_rad = the yaw of pose.pose.orientation, wrapped to (-pi, pi]; linear_velocity_mps =
twist.twist.linear.x; angular_velocity_radps = twist.twist.angular.z. The wheel surface speeds
are v -+ w * track / 2 when the wheel track is given (--wheel-track-m), else NaN (unknown; the
estimator does not read them). A message with a non-finite pose or velocity, or a quaternion
that is no rotation, is refused (OdometryRefused) and counted by the caller.

Encoder ticks (breezyslam format): the differential-drive model of paper eq. 1, as the
synthetic world's odometry (tools/world/odometry_model.h): per interval the wheels turn by
2 pi ticks / ticks_per_turn, travel r times that; the axle centre moves ds = (dl + dr) / 2 and
turns dphi = (dr - dl) / D, then x += ds cos(phi + dphi), y += ds sin(phi + dphi),
phi += dphi; velocities are the interval's increments over its duration (0 for the first
reading and for an interval that is not longer than 0).
"""

import dataclasses
import math

from slammtt.importer.geometry import rotation_from_quaternion, wrap_angle, yaw_of_rotation


class OdometryRefused(ValueError):
    """An odometry message that cannot become an odometry_t (one line why)."""


@dataclasses.dataclass
class Odometry:
    utime: int
    x_m: float
    y_m: float
    heading_rad: float
    linear_mps: float
    angular_radps: float
    left_wheel_mps: float
    right_wheel_mps: float


def odometry_from_ros(msg, utime, wheel_track_m=None):
    position = msg.pose.pose.position
    q = msg.pose.pose.orientation
    linear = float(msg.twist.twist.linear.x)
    angular = float(msg.twist.twist.angular.z)
    values = (position.x, position.y, linear, angular)
    if not all(math.isfinite(float(v)) for v in values):
        raise OdometryRefused(f"pose or velocity not finite ({values})")
    try:
        heading = wrap_angle(yaw_of_rotation(rotation_from_quaternion(q.x, q.y, q.z, q.w)))
    except ValueError as error:
        raise OdometryRefused(str(error)) from None
    left = right = math.nan
    if wheel_track_m is not None:
        left = linear - angular * wheel_track_m / 2.0
        right = linear + angular * wheel_track_m / 2.0
    return Odometry(utime, float(position.x), float(position.y), heading, linear, angular,
                    left, right)


@dataclasses.dataclass(frozen=True)
class WheelGeometry:
    wheel_radius_m: float
    axle_length_m: float      # D: distance between the wheels
    ticks_per_turn: float


class TickIntegrator:
    """Integrates cumulative left/right encoder ticks into odometry, starting at (0, 0, 0)."""

    def __init__(self, geometry):
        self.geometry = geometry
        self._last = None  # (utime, left_ticks, right_ticks)
        self._pose = (0.0, 0.0, 0.0)

    def update(self, utime, left_ticks, right_ticks):
        g = self.geometry
        linear = angular = left_speed = right_speed = 0.0
        if self._last is not None:
            last_utime, last_left, last_right = self._last
            metres_per_tick = 2.0 * math.pi * g.wheel_radius_m / g.ticks_per_turn
            dl = (left_ticks - last_left) * metres_per_tick
            dr = (right_ticks - last_right) * metres_per_tick
            ds = 0.5 * (dl + dr)
            dphi = (dr - dl) / g.axle_length_m
            x, y, phi = self._pose
            phi_next = phi + dphi
            self._pose = (x + ds * math.cos(phi_next), y + ds * math.sin(phi_next),
                          wrap_angle(phi_next))
            dt = (utime - last_utime) * 1e-6
            if dt > 0.0:
                linear, angular = ds / dt, dphi / dt
                left_speed, right_speed = dl / dt, dr / dt
        self._last = (utime, left_ticks, right_ticks)
        x, y, phi = self._pose
        return Odometry(utime, x, y, phi, linear, angular, left_speed, right_speed)


def to_message(odometry, sequence):
    from slammtt_msgs import odometry_t
    message = odometry_t()
    message.utime = int(odometry.utime)
    message.sequence = int(sequence)
    message.x_m = float(odometry.x_m)
    message.y_m = float(odometry.y_m)
    message.heading_rad = float(odometry.heading_rad)
    message.linear_velocity_mps = float(odometry.linear_mps)
    message.angular_velocity_radps = float(odometry.angular_radps)
    message.left_wheel_velocity_mps = float(odometry.left_wheel_mps)
    message.right_wheel_velocity_mps = float(odometry.right_wheel_mps)
    return message
