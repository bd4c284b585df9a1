"""slammtt-export on real recordings: a BreezySLAM Mines log (a lab robot's odometry and a Hokuyo
URG's 682-beam scans, in ../shared) and a leg_tracker bag with leg labels (shipped in tests/data),
each imported and replayed through the stack, then every export read back. A real log has no
ground truth: no truth trajectory, no MOT truth, no world frame; everything else is there."""

import math
import subprocess

import pytest

from conftest import (BIN_DIR, POSITIVE_FIXTURE, import_ok, export_ok, read_log)
from test_export_mcap import read_mcap

REPLAY = BIN_DIR / "slammtt-replay"


def imported_and_replayed(source, tmp_path):
    if not REPLAY.exists():
        pytest.skip(f"{REPLAY} is not built: the tests on replayed recordings are skipped")
    imported = tmp_path / "imported.lcm"
    import_ok(source, "-o", imported)
    log = tmp_path / "replayed.lcm"
    done = subprocess.run([str(REPLAY), "-q", "--no-timing", str(imported), "-o", str(log),
                           "--config", str(tmp_path / "imported.lcm.mount.yaml")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return log, tmp_path / "imported.lcm.mount.yaml"


def test_breezyslam_mines_log(shared_real, tmp_path):
    log, config = imported_and_replayed(shared_real / "breezyslam_mines" / "exp1.dat", tmp_path)
    out = tmp_path / "export"
    err = export_ok(log, "-o", out, "--config", config)
    messages = read_log(log)
    assert len(messages["LASER_SCAN"]) == 756 and "GROUND_TRUTH" not in messages

    from evo.tools import file_interface
    estimate = file_interface.read_tum_trajectory_file(str(out / "tum" / "estimate.tum"))
    odometry = file_interface.read_tum_trajectory_file(str(out / "tum" / "odometry.tum"))
    assert estimate.num_poses == len(messages["POSE"]) == 756
    assert odometry.num_poses == len(messages["ODOMETRY"])
    assert not (out / "tum" / "truth.tum").exists()
    # The robot drove through rooms and a corridor: tens of metres of path.
    assert estimate.path_length > 20.0
    # MOT: no truth; the tracks, in the map frame, one frame per TRACKS message.
    assert "MOT: 756 frames, 0 truth rows" in err and "(frame map)" in err
    assert not (out / "mot" / "gt").exists()

    summary, _, mcap = read_mcap(out / "replayed.mcap")
    topics = {c.topic for c in summary.channels.values()}
    assert topics == {"/tf", "/laser_scan", "/laser_scan/points", "/pose", "/odometry", "/map",
                      "/tracks", "/features"}
    # The Hokuyo's beams are evenly spaced: the LaserScan holds every range unchanged.
    scan, beams = mcap["/laser_scan"][100][1], messages["LASER_SCAN"][100]
    assert len(scan.ranges) == beams.num_beams == 682
    for i in range(0, 682, 31):
        if beams.valid[i]:
            assert scan.ranges[i] == pytest.approx(beams.range_m[i], rel=1e-7)
        else:
            assert math.isnan(scan.ranges[i])
    frames = {(t.parent_frame_id, t.child_frame_id) for _, m in mcap["/tf"] for t in m.transforms}
    assert ("world", "map") not in frames                 # no truth to anchor to
    assert {("map", "base_link"), ("base_link", "laser"), ("map", "odom")} <= frames
    final = messages["MAP"][-1]
    ids = sorted(e.id for e in mcap["/map"][-1][1].entities)
    assert len(final.landmarks) > 0 and len(final.lines) > 0     # the mine's walls are lines
    assert ids == sorted([f"landmark/{l.id}" for l in final.landmarks] +
                         [f"line/{l.id}" for l in final.lines])


def test_leg_tracker_bag_with_labels(tmp_path):
    log, config = imported_and_replayed(POSITIVE_FIXTURE, tmp_path)
    out = tmp_path / "run.mcap"
    export_ok(log, "--mcap", out, "--config", config)
    messages = read_log(log)
    _, _, mcap = read_mcap(out)
    labels = messages["LEG_LABELS"]
    assert len(mcap["/leg_labels"]) == len(labels) == 20
    for (_, update), message in zip(mcap["/leg_labels"], labels):
        entity = update.entities[0]
        assert entity.frame_id == "laser" and len(entity.spheres) == message.num_legs
        for sphere, x, y in zip(entity.spheres, message.x_m, message.y_m):
            assert (sphere.pose.position.x, sphere.pose.position.y) == (x, y)
    # Without ODOMETRY: map -> base_link from the estimate alone.
    assert "/odometry" not in mcap and len(mcap["/pose"]) == len(messages["POSE"])
