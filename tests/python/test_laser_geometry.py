"""LASER_GEOMETRY (laser_geometry_t) in Python: the generated type round-trips through
slammtt.msgs.decode, slammtt-world's log carries its scenario's laser, and slammtt-import writes
the mount it chose with the view the beams span (docs/estimator.md, "Laser geometry")."""

import math
import subprocess

import numpy as np
import pytest

from slammtt import msgs
from slammtt.importer.laser_geometry import View, view_of_beams
from slammtt.lcmlog import LogReader

from conftest import BIN_DIR, POSITIVE_FIXTURE, import_ok, read_log
from synthetic_bags import quaternion_yaw
from test_rosbag_import import robot_bag


def test_the_message_decodes_by_its_fingerprint():
    from slammtt_msgs import laser_geometry_t
    m = laser_geometry_t()
    m.utime = 1700000000000000
    m.mount_forward_m, m.mount_left_m, m.mount_yaw_rad = 0.1, -0.02, math.pi / 2
    m.view_start_rad, m.view_end_rad = -2.0, 1.5
    m.range_min_m, m.range_max_m = 0.15, math.inf
    m.source = "a test"
    decoded = msgs.decode(m.encode())
    assert isinstance(decoded, laser_geometry_t)
    assert (decoded.utime, decoded.mount_forward_m, decoded.mount_left_m,
            decoded.mount_yaw_rad) == (m.utime, 0.1, -0.02, math.pi / 2)
    assert (decoded.view_start_rad, decoded.view_end_rad) == (-2.0, 1.5)
    assert (decoded.range_min_m, decoded.range_max_m) == (0.15, math.inf)
    assert decoded.source == "a test"
    with pytest.raises(msgs.UndecodableMessage):
        msgs.decode(m.encode()[:20])  # ends inside mount_forward_m


def test_a_world_log_carries_its_scenarios_laser(tmp_path):
    log = tmp_path / "s2.lcm"
    subprocess.run([str(BIN_DIR / "slammtt-world"), "--scenario", "s2-lobby", "--duration", "3",
                    "--log", str(log)], check=True, capture_output=True, timeout=120)
    channels = [m.channel for m in LogReader(log)]
    # At the start: the first odometry, then the geometry, before the first frame.
    assert channels[:3] == ["ODOMETRY", "LASER_GEOMETRY", "GROUND_TRUTH"]
    geometries = read_log(log)["LASER_GEOMETRY"]
    assert len(geometries) == 4  # frames 0, 8, 16, 24 of 25 (8 Hz, 3 s)
    for g in geometries:
        assert (g.mount_forward_m, g.mount_left_m, g.mount_yaw_rad) == (0.1, 0.0, 0.0)
        assert (g.view_start_rad, g.view_end_rad) == (-math.pi / 2, math.pi / 2)
        assert (g.range_min_m, g.range_max_m) == (0.1, 30.0)
        assert g.source == "slammtt-world, scenario s2-lobby"
    assert [g.utime - geometries[0].utime for g in geometries] == [0, 1_000_000, 2_000_000,
                                                                   3_000_000]


@pytest.mark.parametrize("angles_deg, start_deg, end_deg", [
    (np.arange(-135.0, 135.01, 0.25), -135.0, 135.0),        # a Hokuyo, centred
    (np.arange(0.0, 360.0, 1.0), -180.0, 180.0),             # a full revolution
    (np.arange(90.0, 270.01, 0.5), 90.0, 270.0),             # centred backwards: across +-180
    (np.arange(-30.0, 120.01, 1.0), -30.0, 120.0),           # not centred
])
def test_the_view_is_what_the_beams_span(angles_deg, start_deg, end_deg):
    view = view_of_beams(np.radians(angles_deg))
    width = view.end_rad - view.start_rad
    assert math.degrees(width) == pytest.approx(end_deg - start_deg, abs=1e-6)
    assert math.degrees(view.start_rad) % 360.0 == pytest.approx(start_deg % 360.0, abs=1e-6)
    # Both ends within a turn of 0, the middle in (-pi, pi].
    assert -math.pi < 0.5 * (view.start_rad + view.end_rad) <= math.pi
    assert view_of_beams([0.3]) == View()


def test_the_import_writes_the_geometry_at_the_first_scan_and_every_second(tmp_path):
    out = tmp_path / "p1.lcm"
    import_ok(POSITIVE_FIXTURE, "-o", out)
    log = read_log(out)
    scans, geometries = log["LASER_SCAN"], log["LASER_GEOMETRY"]
    assert geometries[0].utime == scans[0].utime
    expected = []
    for scan in scans:
        if not expected or scan.utime >= expected[-1] + 1_000_000:
            expected.append(scan.utime)
    assert [g.utime for g in geometries] == expected and len(expected) == 3  # 2.5 s of scans
    g = geometries[0]
    # The fixture's laser: 768 beams from -135 degrees by 0.3516 degrees, 0.03 to 11 m.
    assert math.degrees(g.view_start_rad) == pytest.approx(-135.0, abs=1e-4)
    assert math.degrees(g.view_end_rad) == pytest.approx(-135.0 + 767 * 0.3515625, abs=1e-3)
    assert (g.range_min_m, g.range_max_m) == pytest.approx((0.03, 11.0))
    assert g.source.startswith("slammtt-import, laser topic /training_scan (frame right_laser)")


def test_rotate_to_base_turns_the_view_and_leaves_no_yaw(tmp_path):
    path = robot_bag(mount_q=quaternion_yaw(math.pi / 2)).write(tmp_path / "yawed.bag")
    import_ok(path, "-o", tmp_path / "y.lcm")
    import_ok(path, "-o", tmp_path / "r.lcm", "--rotate-to-base")
    plain = read_log(tmp_path / "y.lcm")["LASER_GEOMETRY"][0]
    turned = read_log(tmp_path / "r.lcm")["LASER_GEOMETRY"][0]
    assert plain.mount_yaw_rad == pytest.approx(math.pi / 2)
    assert turned.mount_yaw_rad == 0.0
    assert turned.view_start_rad == pytest.approx(plain.view_start_rad + math.pi / 2, abs=1e-6)
    assert turned.view_end_rad == pytest.approx(plain.view_end_rad + math.pi / 2, abs=1e-6)



def test_the_foxglove_converter_takes_the_mount_from_the_stream_when_told():
    from slammtt.foxglove.convert import Converter
    from slammtt.stackconfig import CHANNEL_DEFAULTS
    from slammtt_msgs import laser_geometry_t
    m = laser_geometry_t()
    m.utime = 5_000_000
    m.mount_forward_m, m.mount_left_m, m.mount_yaw_rad = 0.2, -0.1, math.pi / 2
    m.view_start_rad, m.view_end_rad, m.range_max_m = -math.pi, math.pi, 12.0
    configured = Converter(CHANNEL_DEFAULTS, (0.05, 0.0))
    configured.convert("LASER_GEOMETRY", m)
    assert configured.mount == (0.05, 0.0, 0.0)   # the configuration's stays
    logged = Converter(CHANNEL_DEFAULTS, mount_from_log=True)
    first = logged.convert("LASER_GEOMETRY", m)
    assert logged.mount == (0.2, -0.1, math.pi / 2)
    # The new base_link -> laser goes out at once, as a /tf message; the same geometry again
    # sends nothing more (the constants are republished once a second).
    assert [o.topic for o in first] == ["/tf"]
    m.utime += 100_000
    assert logged.convert("LASER_GEOMETRY", m) == []
