"""The laser mount: tf chains, yaw, upside-down and tilted lasers, the YAML snippet."""

import math
import types

import numpy as np
import pytest

from slammtt.importer.geometry import Transform, rotation_from_quaternion, wrap_angle
from slammtt.importer.mount import Mount, TransformTree

from synthetic_bags import quaternion_roll_yaw, quaternion_yaw


def stamped(parent, child, xyz, q):
    ns = types.SimpleNamespace
    return ns(header=ns(frame_id=parent), child_frame_id=child,
              transform=ns(translation=ns(x=xyz[0], y=xyz[1], z=xyz[2]),
                           rotation=ns(x=q[0], y=q[1], z=q[2], w=q[3])))


def test_a_chain_of_static_transforms_composes():
    tree = TransformTree()
    # base_link -> plate: 0.2 forward, turned 90 deg; plate -> laser: 0.1 along the plate's x.
    tree.add(stamped("/base_link", "plate", (0.2, 0.0, 0.3), quaternion_yaw(math.pi / 2)), True)
    tree.add(stamped("plate", "laser", (0.1, 0.0, 0.0), quaternion_yaw(0.1)), True)
    transform, source = tree.lookup("base_link", "laser")
    mount = Mount.from_transform(transform, source)
    assert mount.forward_m == pytest.approx(0.2)
    assert mount.left_m == pytest.approx(0.1)
    assert mount.yaw_rad == pytest.approx(math.pi / 2 + 0.1)
    assert not mount.upside_down and mount.tilt_rad == pytest.approx(0.0, abs=1e-7)
    assert source == "/tf_static"
    # Walked the other way round (laser is the parent of base_link).
    inverse = TransformTree()
    inverse.add(stamped("laser", "base_link", (0.0, 0.0, 0.0), quaternion_yaw(0.0)), True)
    assert inverse.lookup("base_link", "laser")[0].close_to(Transform.identity())
    assert tree.lookup("base_link", "elsewhere") is None


def test_tf_transforms_count_only_when_constant():
    tree = TransformTree()
    for _ in range(3):
        tree.add(stamped("base_link", "laser", (0.3, -0.1, 0.0), quaternion_yaw(0.0)), False)
    for k in range(3):
        tree.add(stamped("odom", "base_link", (0.1 * k, 0.0, 0.0), quaternion_yaw(0.0)), False)
    transform, source = tree.lookup("base_link", "laser")
    assert transform.translation[:2].tolist() == pytest.approx([0.3, -0.1])
    assert source == "/tf, constant"
    assert tree.lookup("odom", "base_link") is None
    assert tree.changing() == ["odom -> base_link"]


def test_bad_transforms_are_counted_not_used():
    tree = TransformTree()
    tree.add(stamped("base_link", "laser", (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)), True)
    tree.add(stamped("base_link", "laser", (math.nan, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)), True)
    assert tree.rejected == 2 and tree.lookup("base_link", "laser") is None


def test_upside_down_laser_mirrors_its_beams():
    r = rotation_from_quaternion(*quaternion_roll_yaw(math.pi, 0.5))
    mount = Mount.from_transform(Transform(r, np.array([0.1, 0.0, 0.2])), "test")
    assert mount.upside_down and mount.yaw_rad == pytest.approx(0.5)
    # A beam at +0.3 rad in the laser frame points at 0.5 - 0.3 in the robot frame.
    assert mount.beam_angles_in_base([0.3])[0] == pytest.approx(0.2)
    direction = r @ np.array([math.cos(0.3), math.sin(0.3), 0.0])
    assert math.atan2(direction[1], direction[0]) == pytest.approx(0.2)
    x, y = mount.point_in_base_orientation(1.0, 0.5)
    expected = r @ np.array([1.0, 0.5, 0.0])
    assert (x, y) == pytest.approx((expected[0], expected[1]))
    assert any("upside down" in line for line in mount.warnings(rotated_to_base=False))


def test_tilt_is_reported():
    r = rotation_from_quaternion(math.sin(0.05), 0.0, 0.0, math.cos(0.05))  # roll 0.1 rad
    mount = Mount.from_transform(Transform(r, np.zeros(3)), "test")
    assert mount.tilt_rad == pytest.approx(0.1)
    assert any("tilted by 5.73 deg" in line for line in mount.warnings(rotated_to_base=True))


def test_yaw_goes_into_the_yaml():
    mount = Mount(forward_m=0.25, left_m=-0.05, yaw_rad=math.radians(90), source="test")
    assert not mount.warnings(rotated_to_base=False)  # the estimator takes the yaw
    assert not mount.warnings(rotated_to_base=True)
    text = mount.yaml(["header"], rotated_to_base=False)
    assert text == ("# header\nestimator:\n  sensor_forward_m: 0.25\n  sensor_left_m: -0.05\n"
                    "  sensor_yaw_deg: 90.0\n")
    rotated = mount.yaml(["header"], rotated_to_base=True)
    assert "  sensor_yaw_deg: 0.0\n# sensor yaw 90.0 deg: already applied" in rotated
    assert Mount().warnings(rotated_to_base=False) == []


def test_wrap_angle_matches_common_angle_h():
    assert wrap_angle(math.pi) == math.pi
    assert wrap_angle(-math.pi) == math.pi
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
