"""Rigid transforms in 3D (tf's translation + unit quaternion) and the planar angles of the stack.

Quaternions are (x, y, z, w) as in geometry_msgs/Quaternion. A Transform maps points of its child
frame into its parent frame: p_parent = R p_child + t (tf's convention for parent -> child).
"""

import dataclasses
import math

import numpy as np


def wrap_angle(angle_rad):
    """The angle in (-pi, pi], as common/angle.h's WrapAngle."""
    wrapped = math.remainder(angle_rad, 2.0 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def wrap_angles(angles_rad):
    """wrap_angle of every element of an array (float64)."""
    a = np.asarray(angles_rad, dtype=np.float64)
    wrapped = np.remainder(a + math.pi, 2.0 * math.pi) - math.pi
    # remainder gives [-pi, pi): -pi belongs to pi.
    wrapped[wrapped <= -math.pi] = math.pi
    return wrapped


def rotation_from_quaternion(x, y, z, w):
    """The 3x3 rotation of a quaternion, normalised first. ValueError when it has no direction
    (zero or not finite)."""
    q = np.array([x, y, z, w], dtype=np.float64)
    norm = float(np.linalg.norm(q))
    if not math.isfinite(norm) or norm < 1e-9:
        raise ValueError(f"quaternion ({x}, {y}, {z}, {w}) is not a rotation")
    x, y, z, w = q / norm
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def yaw_of_rotation(rotation):
    """Heading of the rotated x axis in the parent's xy plane (the yaw of a ZYX decomposition)."""
    return math.atan2(rotation[1, 0], rotation[0, 0])


@dataclasses.dataclass(frozen=True)
class Transform:
    rotation: np.ndarray      # 3x3
    translation: np.ndarray   # 3

    @staticmethod
    def identity():
        return Transform(np.eye(3), np.zeros(3))

    @staticmethod
    def from_ros(translation, quaternion):
        """From geometry_msgs/Transform fields (objects with x, y, z and x, y, z, w)."""
        t = np.array([translation.x, translation.y, translation.z], dtype=np.float64)
        if not np.all(np.isfinite(t)):
            raise ValueError(f"translation {t.tolist()} is not finite")
        r = rotation_from_quaternion(quaternion.x, quaternion.y, quaternion.z, quaternion.w)
        return Transform(r, t)

    def then(self, child):
        """parent<-self.child composed with self.child<-child.child: parent<-child.child."""
        return Transform(self.rotation @ child.rotation,
                         self.rotation @ child.translation + self.translation)

    def inverse(self):
        rt = self.rotation.T
        return Transform(rt, -rt @ self.translation)

    def close_to(self, other, tolerance=1e-6):
        return (np.allclose(self.rotation, other.rotation, atol=tolerance, rtol=0)
                and np.allclose(self.translation, other.translation, atol=tolerance, rtol=0))
