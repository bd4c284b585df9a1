"""slammtt-import on ROS 1 bags: the leg_tracker fixture, synthetic bags with odometry, tf and
labels, stamps out of order, damaged bags, the command line."""

import math
import os
import shutil
import subprocess

import numpy as np
import pytest
from rosbags.highlevel import AnyReader

from conftest import BIN_DIR, DEMO_FIXTURE, POSITIVE_FIXTURE, import_ok, read_log, run_import
from synthetic_bags import Bag, quaternion_roll_yaw, quaternion_yaw


def bag_messages(path, topic):
    with AnyReader([path]) as reader:
        chosen = [c for c in reader.connections if c.topic == topic]
        return [reader.deserialize(raw, c.msgtype) for c, _, raw in reader.messages(chosen)]


def stamp_us(header):
    return header.stamp.sec * 1_000_000 + header.stamp.nanosec // 1000


def test_fixture_scans_and_labels(tmp_path):
    out = tmp_path / "p1.lcm"
    err = import_ok(POSITIVE_FIXTURE, "-o", out)
    assert "sensor_msgs/LaserScan topic /training_scan (the only one)" in err
    assert "LEG_LABELS: 20 labelled scans, 30 legs" in err
    log = read_log(out)
    assert set(log) == {"LASER_SCAN", "LEG_LABELS", "LASER_GEOMETRY"}
    scans, labels = log["LASER_SCAN"], log["LEG_LABELS"]
    source_scans = bag_messages(POSITIVE_FIXTURE, "/training_scan")
    source_labels = bag_messages(POSITIVE_FIXTURE, "/leg_cluster_positions")
    assert len(scans) == len(source_scans) == 20
    for k, (scan, source) in enumerate(zip(scans, source_scans)):
        assert scan.utime == stamp_us(source.header)
        assert scan.sequence == k
        assert scan.num_beams == 768
        assert np.array_equal(np.float32(scan.range_m), source.ranges, equal_nan=True)
        angles = source.angle_min + np.arange(768) * np.float64(source.angle_increment)
        np.testing.assert_allclose(scan.angle_rad, angles, atol=1e-6)
        assert scan.range_min_m == pytest.approx(0.03)
        assert scan.scan_duration_us == round(source.time_increment * 767 * 1e6)
    # Each label (stamp 0) labels the scan after it, in the laser frame.
    assert [label.utime for label in labels] == [scan.utime for scan in scans]
    for label, source in zip(labels, source_labels):
        assert list(label.x_m) == [p.position.x for p in source.poses]
        assert list(label.y_m) == [p.position.y for p in source.poses]
    assert sum(label.num_legs for label in labels) == 30


def test_same_input_same_bytes(tmp_path):
    for name in ("a", "b"):
        import_ok(POSITIVE_FIXTURE, "-o", tmp_path / f"{name}.lcm")
    assert (tmp_path / "a.lcm").read_bytes() == (tmp_path / "b.lcm").read_bytes()
    assert (tmp_path / "a.lcm.mount.yaml").read_text() == \
        (tmp_path / "b.lcm.mount.yaml").read_text()


def test_demo_fixture_and_its_nan_beams(tmp_path):
    out = tmp_path / "demo.lcm"
    err = import_ok(DEMO_FIXTURE, "-o", out)
    assert "LASER_SCAN: 31 scans of 512 beams; REP 117: 5129 valid, 10641 no return, " \
           "0 too close, 102 invalid, 0 below min, 0 above max" in err
    assert "leg labels" not in err
    scans = read_log(out)["LASER_SCAN"]
    assert all(not scan.valid[i] for scan in scans for i in range(512)
               if math.isnan(scan.range_m[i]) or math.isinf(scan.range_m[i]))


def robot_bag(ros_version=1, mount_q=quaternion_yaw(0.0), mount_xyz=(0.2, 0.05, 0.3)):
    """Two lasers, odometry, /tf_static base_link -> laser, /tf odom -> base_link."""
    bag = Bag(ros_version)
    bag.tf("/tf_static", 0, [bag.transform(0, "base_link", "laser", mount_xyz, mount_q)])
    for k in range(5):
        t = 1_000_000 + k * 100_000
        bag.odometry("/odom", t - 10_000, 0.1 * k, 0.0, 0.05 * k, 1.0, 0.5)
        bag.tf("/tf", t - 10_000, [bag.transform(t, "odom", "base_link", (0.1 * k, 0, 0),
                                                 quaternion_yaw(0.05 * k))])
        bag.scan("/front_scan", t, [1.0, math.inf, 2.0], frame="laser")
        bag.scan("/rear_scan", t + 1, [3.0, 3.0, 3.0], frame="rear_laser")
    return bag


def test_odometry_tf_mount_and_topic_choice(tmp_path):
    path = robot_bag().write(tmp_path / "robot.bag")
    out = tmp_path / "robot.lcm"
    err = import_ok(path, "-o", out, "--wheel-track-m", "0.4")
    assert "sensor_msgs/LaserScan topic /front_scan: the first of 2 (/front_scan, " \
           "/rear_scan); choose another with --laser-topic" in err
    assert "nav_msgs/Odometry topic /odom (the only one)" in err
    assert "mount: forward 0.2000 m, left 0.0500 m, yaw 0.00 deg (static transform " \
           "base_link -> laser from /tf_static)" in err
    log = read_log(out)
    odometry = log["ODOMETRY"]
    assert [m.utime for m in odometry] == [990_000 + k * 100_000 for k in range(5)]
    last = odometry[-1]
    assert (last.x_m, last.heading_rad, last.linear_velocity_mps,
            last.angular_velocity_radps) == pytest.approx((0.4, 0.2, 1.0, 0.5))
    assert (last.left_wheel_velocity_mps, last.right_wheel_velocity_mps) == \
        pytest.approx((0.9, 1.1))
    assert [m.sequence for m in odometry] == list(range(5))
    assert (tmp_path / "robot.lcm.mount.yaml").read_text().splitlines()[2:5] == [
        "estimator:", "  sensor_forward_m: 0.2", "  sensor_left_m: 0.05"]
    # Odometry before each scan of the same moment: merged by utime.
    from slammtt.lcmlog import LogReader
    channels = [m.channel for m in LogReader(out)]
    # The laser's geometry at the first scan (the next second starts after the last scan).
    assert channels == ["ODOMETRY", "LASER_GEOMETRY", "LASER_SCAN"] + \
        ["ODOMETRY", "LASER_SCAN"] * 4
    geometry = log["LASER_GEOMETRY"][0]
    assert geometry.utime == 1_000_000
    assert (geometry.mount_forward_m, geometry.mount_left_m, geometry.mount_yaw_rad) == \
        pytest.approx((0.2, 0.05, 0.0))

    rear = tmp_path / "rear.lcm"
    err = import_ok(path, "-o", rear, "--laser-topic", "/rear_scan", "--no-odometry",
                    "--channel", "laser_scan=REAR")
    assert "topic /rear_scan (chosen by --laser-topic)" in err
    assert "no static transform base_link -> rear_laser" in err
    log = read_log(rear)
    assert set(log) == {"REAR", "LASER_GEOMETRY"}
    assert list(log["REAR"][0].range_m) == [3.0, 3.0, 3.0]


def test_wheel_speeds_unknown_without_the_track(tmp_path):
    path = robot_bag().write(tmp_path / "robot.bag")
    import_ok(path, "-o", tmp_path / "r.lcm")
    last = read_log(tmp_path / "r.lcm")["ODOMETRY"][-1]
    assert math.isnan(last.left_wheel_velocity_mps) and math.isnan(last.right_wheel_velocity_mps)


def test_options_override_the_transform_with_a_warning(tmp_path):
    path = robot_bag().write(tmp_path / "robot.bag")
    err = import_ok(path, "-o", tmp_path / "o.lcm", "--mount-forward-m", "0.5")
    assert "warning: the options' mount differs from the bag's transform" in err
    assert "mount: forward 0.5000 m, left 0.0500 m" in err


def test_yawed_laser_gives_the_estimator_its_yaw_or_rotate_to_base_turns_the_beams(tmp_path):
    path = robot_bag(mount_q=quaternion_yaw(math.pi / 2)).write(tmp_path / "yawed.bag")
    err = import_ok(path, "-o", tmp_path / "y.lcm")
    assert "yaw" not in "".join(l for l in err.splitlines() if "warning" in l)
    assert "  sensor_yaw_deg: 90.0\n" in (tmp_path / "y.lcm.mount.yaml").read_text()
    plain = read_log(tmp_path / "y.lcm")["LASER_SCAN"][0]
    err = import_ok(path, "-o", tmp_path / "r.lcm", "--rotate-to-base")
    assert "yaw" not in "".join(l for l in err.splitlines() if "warning" in l)
    turned = read_log(tmp_path / "r.lcm")["LASER_SCAN"][0]
    np.testing.assert_allclose(turned.angle_rad, np.array(plain.angle_rad) + math.pi / 2,
                               atol=1e-6)
    assert "already applied" in (tmp_path / "r.lcm.mount.yaml").read_text()


def test_upside_down_laser(tmp_path):
    path = robot_bag(mount_q=quaternion_roll_yaw(math.pi, 0.0)).write(tmp_path / "flip.bag")
    err = import_ok(path, "-o", tmp_path / "f.lcm", "--rotate-to-base")
    assert "upside down" in err
    scan = read_log(tmp_path / "f.lcm")["LASER_SCAN"][0]
    np.testing.assert_allclose(scan.angle_rad, [1.0, 0.99, 0.98], atol=1e-6)


def test_labels_in_another_frame_are_moved_or_skipped(tmp_path):
    bag = Bag()
    bag.tf("/tf_static", 0, [bag.transform(0, "laser", "marker_frame", (1.0, 0.0, 0.0),
                                           quaternion_yaw(math.pi / 2))])
    bag.pose_array("/leg_cluster_positions", 0, [(0.5, 0.0)], "marker_frame", 900_000)
    bag.scan("/scan", 1_000_000, [1.0], frame="laser")
    bag.pose_array("/leg_cluster_positions", 0, [(0.5, 0.0)], "nowhere", 1_050_000)
    bag.scan("/scan", 1_100_000, [1.0], frame="laser")
    bag.pose_array("/leg_cluster_positions", 1_100_000, [(2.0, 1.0)], "laser", 1_150_000)
    bag.pose_array("/leg_cluster_positions", 0, [(7.0, 7.0)], "laser", 1_200_000)
    bag.pose_array("/leg_cluster_positions", 0, [(1.0, 1.0)] * 1001, "laser", 1_250_000)
    bag.pose_array("/leg_cluster_positions", 0, [(math.nan, 1.0)], "laser", 1_260_000)
    path = bag.write(tmp_path / "labels.bag")
    err = import_ok(path, "-o", tmp_path / "l.lcm")
    assert "skipped 1 label messages in frame nowhere" in err
    assert "skipped 1 /leg_cluster_positions messages without a following scan" in err
    assert "skipped 1 label messages with more than 1000 positions" in err
    assert "skipped 1 label messages with non-finite positions" in err
    labels = read_log(tmp_path / "l.lcm")["LEG_LABELS"]
    assert [m.utime for m in labels] == [1_000_000, 1_100_000]
    assert (labels[0].x_m[0], labels[0].y_m[0]) == pytest.approx((1.0, 0.5))
    assert (list(labels[1].x_m), list(labels[1].y_m)) == ([2.0], [1.0])
    err = import_ok(path, "-o", tmp_path / "n.lcm", "--no-labels")
    assert "LEG_LABELS" not in read_log(tmp_path / "n.lcm")


def test_stamps_out_of_order_are_kept_and_reported(tmp_path):
    bag = Bag()
    for k, stamp in enumerate([1_000_000, 1_100_000, 1_050_000, 1_050_000, 1_200_000]):
        bag.scan("/scan", stamp, [1.0], bag_time_us=2_000_000 + k * 100_000)
    path = bag.write(tmp_path / "order.bag")
    err = import_ok(path, "-o", tmp_path / "o.lcm")
    assert "LASER_SCAN: 1 utimes go backwards and 1 repeat (first at message 2: utime " \
           "1050000 after 1100000); the stack drops" in err
    assert [m.utime for m in read_log(tmp_path / "o.lcm")["LASER_SCAN"]] == \
        [1_000_000, 1_100_000, 1_050_000, 1_050_000, 1_200_000]
    import_ok(path, "-o", tmp_path / "b.lcm", "--time-source", "bag")
    assert [m.utime for m in read_log(tmp_path / "b.lcm")["LASER_SCAN"]] == \
        [2_000_000 + k * 100_000 for k in range(5)]


def test_refused_messages_are_counted(tmp_path):
    bag = Bag()
    bag.scan("/scan", 1_000_000, [1.0, 2.0])
    bag.scan("/scan", 1_100_000, [1.0, 2.0], increment=0.0)
    bag.scan("/scan", 1_200_000, [1.0, 2.0], frame="other")
    bag.odometry("/odom", 1_000_000, math.nan, 0.0, 0.0, 0.0, 0.0)
    bag.odometry("/odom", 1_100_000, 0.0, 0.0, 0.0, 0.0, 0.0)
    path = bag.write(tmp_path / "bad.bag")
    err = import_ok(path, "-o", tmp_path / "b.lcm")
    assert "skipped 1 /scan scans refused (first: angle_increment 0 with 2 beams)" in err
    assert "skipped 1 /scan scans in another frame than laser (first: frame other)" in err
    assert "skipped 1 /odom messages refused (first: pose or velocity not finite" in err
    log = read_log(tmp_path / "b.lcm")
    assert len(log["LASER_SCAN"]) == 1 and len(log["ODOMETRY"]) == 1


@pytest.mark.parametrize("damage", ["truncated", "garbage", "empty", "text"])
def test_damaged_bags_fail_with_one_line_and_no_output(tmp_path, damage):
    data = POSITIVE_FIXTURE.read_bytes()
    damaged = tmp_path / "damaged.bag"
    damaged.write_bytes({"truncated": data[:len(data) // 2],
                         "garbage": data[:4096] + bytes(range(256)) * 40,
                         "empty": b"",
                         "text": b"not a bag\n"}[damage])
    out = tmp_path / "out.lcm"
    status, _, err = run_import(damaged, "-o", out)
    assert status == 1
    assert len(err.strip().splitlines()) == 1
    assert err.startswith(f"slammtt-import: error: {damaged}: ")
    assert not out.exists() and not (tmp_path / "out.lcm.partial").exists()


def test_a_corrupt_message_inside_a_bag_is_skipped(tmp_path):
    bag = Bag()
    bag.scan("/scan", 1_000_000, [1.0, 2.0])
    bag.scan("/scan", 1_100_000, [3.0, 4.0])
    path = bag.write(tmp_path / "ok.bag")
    data = bytearray(path.read_bytes())
    # The second scan's ranges array count (ROS 1 serialisation: uint32 before the floats).
    at = data.rfind(np.float32([3.0, 4.0]).tobytes()) - 4
    data[at:at + 4] = (10_000).to_bytes(4, "little")
    path.write_bytes(bytes(data))
    status, _, err = run_import(path, "-o", tmp_path / "o.lcm")
    assert status == 0, err
    assert "skipped 1 /scan messages (undecodable)" in err
    assert len(read_log(tmp_path / "o.lcm")["LASER_SCAN"]) == 1


def test_command_line(tmp_path):
    status, out, err = run_import("--help")
    assert status == 0 and "--laser-topic" in out and "--rotate-to-base" in out
    status, out, _ = run_import("--version")
    assert status == 0 and out.strip() == "slammtt-import 0.1.0"
    for args in (["x.bag"], ["x.bag", "-o", "y.lcm", "--bogus"],
                 [POSITIVE_FIXTURE, "-o", "y.lcm", "--mount-forward-m", "nan"],
                 [POSITIVE_FIXTURE, "-o", "y.lcm", "--channel", "nope=X"],
                 [POSITIVE_FIXTURE, "-o", "y.lcm", "--channel", "laser_scan"],
                 [POSITIVE_FIXTURE, "-o", "y.lcm", "--no-labels", "--labels-topic", "/x"],
                 [POSITIVE_FIXTURE, "-o", "y.lcm", "--format", "csv"]):
        status, _, err = run_import(*args)
        assert status == 2, args
        assert len(err.strip().splitlines()) == 1, err
        assert err.startswith("slammtt-import: error: ") and err.strip().endswith("(see --help)")
    status, _, err = run_import(POSITIVE_FIXTURE, "-o", tmp_path / "x.lcm",
                                "--laser-topic", "/nope")
    assert status == 1
    assert "--laser-topic /nope: no sensor_msgs/LaserScan topic of that name " \
           "(sensor_msgs/LaserScan topics: /training_scan)" in err
    status, _, err = run_import(tmp_path / "absent.bag", "-o", tmp_path / "x.lcm")
    assert status == 1 and "no such file or folder" in err
    copy = tmp_path / "same.bag"
    shutil.copy(POSITIVE_FIXTURE, copy)
    status, _, err = run_import(copy, "-o", copy)
    assert status == 2 and "the output is the input" in err


def test_launcher_runs_the_venv_program():
    launcher = BIN_DIR / "slammtt-import"
    if not launcher.exists():
        pytest.skip(f"no build at {BIN_DIR}: the launcher is written by CMake")
    done = subprocess.run([launcher, "--version"], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.strip() == "slammtt-import 0.1.0"
    assert os.access(launcher, os.X_OK)
