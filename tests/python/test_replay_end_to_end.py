"""Imported logs through slammtt-replay (LASER_SCAN -> segmenter -> estimator, with and without
ODOMETRY), with the mount file the importer wrote as the configuration; the outputs decoded."""

import math
import subprocess

import pytest

from conftest import BIN_DIR, POSITIVE_FIXTURE, import_ok, read_log
from test_breezyslam import line, ranges
from test_rosbag_import import robot_bag

REPLAY = BIN_DIR / "slammtt-replay"


@pytest.fixture
def replay():
    if not REPLAY.exists():
        pytest.skip(f"{REPLAY} is not built: the end-to-end tests are skipped")

    def run(log, out, *extra):
        done = subprocess.run([REPLAY, log, "-o", out, *map(str, extra)], capture_output=True,
                              text=True, timeout=300)
        assert done.returncode == 0, done.stderr
        return done.stderr
    return run


def test_fixture_without_odometry(tmp_path, replay):
    imported = tmp_path / "p1.lcm"
    import_ok(POSITIVE_FIXTURE, "-o", imported)
    out = tmp_path / "p1-out.lcm"
    err = replay(imported, out, "--config", tmp_path / "p1.lcm.mount.yaml")
    assert "segmenter: handled 20 messages, published 20" in err
    log = read_log(out)
    scans, features = log["LASER_SCAN"], log["FEATURES"]
    assert [f.utime for f in features] == [s.utime for s in scans]
    assert [f.sequence for f in features] == list(range(20))
    assert all(f.num_features + f.num_lines + f.num_people > 0 for f in features)
    for f in features:
        for point in f.features:
            # (Where a feature lies is the segmenter's business; here: usable numbers.)
            assert point.range_m > 0.0 and math.isfinite(point.range_m)
            assert abs(point.bearing_rad) <= math.pi
    assert len(log["POSE"]) == 20 and len(log["LEG_LABELS"]) == 20
    status = log["ESTIMATOR_STATUS"][-1]
    # (the first scan has no previous one to have odometry since)
    assert status.scans_processed == 20 and status.scans_without_odometry == 19
    assert status.messages_undecodable == 0 and status.messages_out_of_order == 0
    # Twice: the same bytes.
    replay(imported, tmp_path / "again.lcm", "--config", tmp_path / "p1.lcm.mount.yaml")
    assert (tmp_path / "again.lcm").read_bytes() == out.read_bytes()


def test_bag_with_odometry_and_mount(tmp_path, replay):
    bag = robot_bag(mount_xyz=(0.25, 0.0, 0.3)).write(tmp_path / "robot.bag")
    imported = tmp_path / "robot.lcm"
    import_ok(bag, "-o", imported)
    out = tmp_path / "robot-out.lcm"
    replay(imported, out, "--config", tmp_path / "robot.lcm.mount.yaml")
    log = read_log(out)
    assert len(log["FEATURES"]) == 5
    status = log["ESTIMATOR_STATUS"][-1]
    assert status.odometry_processed == 5 and status.scans_processed == 5
    assert status.scans_without_odometry == 0


def test_breezyslam_log_with_odometry(tmp_path, replay):
    dat = tmp_path / "drive.dat"
    # A wall 2 m ahead while the robot drives 1 wheel turn (0.48 m) per second.
    wall = ranges(*[(i, 2000) for i in range(250, 432)], fill=0)
    dat.write_text("".join(line(1_000_000 + k * 100_000, 200 * k, 200 * k, wall)
                           for k in range(10)))
    imported = tmp_path / "drive.lcm"
    import_ok(dat, "-o", imported)
    out = tmp_path / "drive-out.lcm"
    replay(imported, out, "--config", tmp_path / "drive.lcm.mount.yaml")
    log = read_log(out)
    assert len(log["FEATURES"]) == 10 and len(log["POSE"]) == 10
    status = log["ESTIMATOR_STATUS"][-1]
    assert status.odometry_processed == 10 and status.scans_processed == 10
    last = log["POSE"][-1]
    assert math.isfinite(last.x_m) and last.x_m > 0.2


def test_shared_recordings_replay(shared_real, tmp_path, replay):
    for source, scans, odometry in [
            (shared_real / "leg_tracker_demo" / "demo_stationary_simple_environment.bag",
             1265, 0),
            (shared_real / "leg_tracker_training" / "negative_2.bag", 435, 0),
            (shared_real / "breezyslam_mines" / "exp1.dat", 756, 756)]:
        imported = tmp_path / f"{source.stem}.lcm"
        import_ok(source, "-o", imported)
        out = tmp_path / f"{source.stem}-out.lcm"
        replay(imported, out, "--config", f"{imported}.mount.yaml", "--no-timing")
        log = read_log(out)
        assert len(log["FEATURES"]) == scans, source
        status = log["ESTIMATOR_STATUS"][-1]
        assert status.scans_processed == scans and status.odometry_processed == odometry
        assert status.messages_out_of_order == 0 and status.restarts == 0
