"""slammtt-eval --plots on real recordings, which have no ground truth: imported with
slammtt-import, replayed with the mount file it wrote, then drawn from the log alone
(docs/tools.md, "Pictures"): exit status 1, no report, the six pictures with what the log holds."""

import re
import subprocess

import pytest

from conftest import BIN_DIR, POSITIVE_FIXTURE, SHARED_REAL, import_ok, read_log

REPLAY = BIN_DIR / "slammtt-replay"
EVAL = BIN_DIR / "slammtt-eval"
PICTURES = ["trajectory.svg", "map.svg", "tracks.svg", "identities.svg", "errors.svg",
            "scan.svg"]
ESTIMATE_COLOUR = 'stroke="#1f77b4"'  # tools/plots/picture_style.cc, EstimateStyle


@pytest.fixture
def draw(tmp_path):
    for program in (REPLAY, EVAL):
        if not program.exists():
            pytest.skip(f"{program} is not built: the picture tests are skipped")

    def run(recording):
        imported = tmp_path / "robot.lcm"
        import_ok(recording, "-o", imported)
        out = tmp_path / "robot-out.lcm"
        subprocess.run([REPLAY, imported, "-o", out, "--config", tmp_path / "robot.lcm.mount.yaml",
                        "--no-timing", "--quiet"], check=True, capture_output=True, timeout=600)
        report = tmp_path / "report.json"
        pictures = tmp_path / "pictures"
        done = subprocess.run([EVAL, out, "--json", report, "--plots", pictures],
                              capture_output=True, text=True, timeout=300)
        assert done.returncode == 1, done.stderr
        assert f"{out}: no GROUND_TRUTH: nothing can be scored; no report written" in done.stderr
        assert f"pictures of what the log holds, nothing scored: {pictures}" in done.stdout
        assert not report.exists()
        svg = {name: (pictures / name).read_text() for name in PICTURES}
        return read_log(out), svg
    return run


def vertices(path_line):
    return len(re.findall(r"[ML]-?[0-9.]+ -?[0-9.]+", path_line))


def check_drawn_from_the_log(log, svg):
    poses = log["POSE"]
    trajectory = svg["trajectory.svg"]
    assert "estimator's map frame, no ground truth" in trajectory
    assert "estimate (POSE)" in trajectory
    estimate = [line for line in trajectory.splitlines()
                if line.startswith("<path") and ESTIMATE_COLOUR in line]
    assert len(estimate) == 1
    assert vertices(estimate[0]) == len(poses)  # every POSE (fewer than 1500: no decimation)
    landmarks = log["MAP"][-1].landmarks
    assert f"{len(landmarks)} landmarks in the last MAP" in svg["map.svg"]
    for landmark in landmarks:
        assert f">{landmark.id}</text>" in svg["map.svg"]
    moving = {t.id for message in log["TRACKS"] for t in message.tracks
              if t.confirmed and t.object_class == t.CLASS_MOVING}
    assert f"{len(moving)} track identities" in svg["tracks.svg"]
    for track_id in moving:
        assert f">{track_id}</text>" in svg["tracks.svg"]
    assert "no ground truth in the log" in svg["identities.svg"]
    assert "no ground truth in the log" in svg["errors.svg"]
    for name, text in svg.items():
        assert "nan" not in text, name


def test_leg_tracker_fixture(draw):
    log, svg = draw(POSITIVE_FIXTURE)
    assert len(log["POSE"]) == 20 and "ODOMETRY" not in log
    check_drawn_from_the_log(log, svg)
    assert "odometry" not in svg["trajectory.svg"]
    assert "(sensor frame)" in svg["scan.svg"]


def test_breezyslam_run_with_odometry(draw):
    recording = SHARED_REAL / "breezyslam_mines" / "exp1.dat"
    if not recording.exists():
        pytest.skip(f"{recording} is absent (../shared): the real robot run is skipped")
    log, svg = draw(recording)
    assert len(log["ODOMETRY"]) > 100
    check_drawn_from_the_log(log, svg)
    assert "odometry (anchored to the estimate at its first pose)" in svg["trajectory.svg"]
