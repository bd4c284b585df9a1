"""slammtt-export of the smoother's outputs (docs/export.md): s1-crossing seed 1 replayed with
slammtt-smoother (`slammtt-replay --smoother`), its SMOOTHED_MAP in smoothed_map.csv and in the
MCAP file's /smoothed_map, its SMOOTHED_POSE in smoothed.tum and its last SMOOTHED_TRAJECTORY in
smoothed_final.tum, read back by the csv module and
the `mcap` library."""

import csv
import subprocess

import pytest

from conftest import REPLAY_PROGRAM, SOURCE_DIR, WORLD, export_ok, read_log
from test_export_mcap import read_mcap


@pytest.fixture(scope="module")
def smoothed(tmp_path_factory):
    for program in (WORLD, REPLAY_PROGRAM):
        if not program.exists():
            pytest.skip(f"{program} is not built: the tests on a scenario's log are skipped")
    directory = tmp_path_factory.mktemp("smoothed")
    config = SOURCE_DIR / "estimator" / "config" / "s1-crossing.yaml"
    world, log = directory / "world.lcm", directory / "replay.lcm"
    for command in ([WORLD, "--scenario", "s1-crossing", "--seed", 1, "--duration", 20,
                     "--log", world],
                    [REPLAY_PROGRAM, "-q", "--no-timing", "--smoother", world, "-o", log,
                     "--config", config]):
        done = subprocess.run(list(map(str, command)), capture_output=True, text=True,
                              timeout=600)
        assert done.returncode == 0, done.stderr
    out = directory / "export"
    export_ok(log, "--csv", out / "csv", "--tum", out / "tum", "--mcap", out / "run.mcap",
              "--config", config)
    return out, read_log(log)


def test_smoothed_map_csv_holds_every_landmark_of_every_smoothed_map(smoothed):
    out, log = smoothed
    with open(out / "csv" / "smoothed_map.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    expected = [(m.utime, l) for m in log["SMOOTHED_MAP"] for l in m.landmarks]
    assert len(expected) > 0, "the smoother mapped nothing: nothing to export"
    assert len(rows) == len(expected)
    for row, (utime, landmark) in zip(rows, expected):
        assert int(row["utime_us"]) == utime and int(row["id"]) == landmark.id
        assert (float(row["x_m"]), float(row["y_m"])) == (landmark.x_m, landmark.y_m)
        assert float(row["var_y_m2"]) == landmark.covariance[3]


def test_mcap_draws_the_smoothed_map_and_tum_has_every_smoothed_pose(smoothed):
    out, log = smoothed
    _, _, messages = read_mcap(out / "run.mcap")
    assert len(messages["/smoothed_map"]) == len(log["SMOOTHED_MAP"])
    _, update = messages["/smoothed_map"][-1]
    final = log["SMOOTHED_MAP"][-1]
    entities = {e.id: e for e in update.entities}
    assert set(entities) == {f"landmark/{l.id}" for l in final.landmarks}
    for l in final.landmarks:
        e = entities[f"landmark/{l.id}"]
        assert e.frame_id == "map" and e.texts[0].text == str(l.id)
        assert (e.spheres[0].pose.position.x, e.spheres[0].pose.position.y) == (l.x_m, l.y_m)
    poses = (out / "tum" / "smoothed.tum").read_text().splitlines()
    assert len(poses) == len(log["SMOOTHED_POSE"]) > 0


def test_tum_has_the_final_smoothed_trajectory_keyframe_by_keyframe(smoothed):
    out, log = smoothed
    final = log["SMOOTHED_TRAJECTORY"][-1]
    assert final.num_poses > 0, "the smoother published an empty trajectory"
    lines = (out / "tum" / "smoothed_final.tum").read_text().splitlines()
    assert len(lines) == final.num_poses
    for line, utime, x, y in zip(lines, final.pose_utime, final.x_m, final.y_m):
        fields = line.split()
        assert float(fields[0]) == pytest.approx(utime * 1e-6, abs=1e-6)
        assert (float(fields[1]), float(fields[2])) == pytest.approx((x, y), abs=1e-9)
