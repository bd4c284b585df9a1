"""slammtt-export's command line, TUM trajectories, CSV tables and MOTChallenge files, read
back by evo, the csv module, TrackEval and py-motmetrics: evo_ape --align_origin reproduces
slammtt-eval's ATE to 1e-6 (docs/export.md)."""

import csv
import math
import re
import subprocess

import pytest

from conftest import BIN_DIR, evo_stats, export_ok, read_log, run_export, scenario_run

# py-motmetrics 1.4.0's reader warns on pandas 3 (motmetrics/io.py subtracts a tuple).
pytestmark = pytest.mark.filterwarnings("ignore:Operation with tuple is deprecated")

SCENARIOS = [("s1-crossing", 7), ("s2-lobby", 3)]


@pytest.fixture(scope="module", params=SCENARIOS, ids=lambda p: f"{p[0]}-seed{p[1]}")
def run(request, tmp_path_factory):
    return scenario_run(tmp_path_factory, *request.param)


@pytest.fixture(scope="module")
def exported(run, tmp_path_factory):
    out = tmp_path_factory.mktemp("export")
    err = export_ok(run.log, "--tum", out / "tum", "--csv", out / "csv", "--mot", out / "mot",
                    "--config", run.config)
    return out, err


def test_evo_ape_align_origin_is_slammtt_evals_ate(run, exported, tmp_path):
    out, err = exported
    stats = evo_stats("evo_ape", "tum", out / "tum" / "truth.tum", out / "tum" / "estimate.tum",
                "--align_origin", home=tmp_path)
    robot = run.report["detail"]["robot"]
    assert stats["rmse"] == pytest.approx(run.report["ate_rmse_m"], abs=1e-6)
    assert stats["max"] == pytest.approx(robot["ate_max_m"], abs=1e-6)
    assert stats["mean"] == pytest.approx(robot["ate_mean_m"], abs=1e-6)
    assert run.report["ate_rmse_m"] > 0.001    # not two empty or identical trajectories


def test_tum_files_hold_every_pose(run, exported):
    out, _ = exported
    log = read_log(run.log)
    from evo.tools import file_interface
    for stem, channel, pose_of in (
            ("estimate", "POSE", lambda m: (m.x_m, m.y_m, m.heading_rad)),
            ("odometry", "ODOMETRY", lambda m: (m.x_m, m.y_m, m.heading_rad)),
            ("truth", "GROUND_TRUTH",
             lambda m: (m.robot_x_m, m.robot_y_m, m.robot_heading_rad))):
        trajectory = file_interface.read_tum_trajectory_file(str(out / "tum" / f"{stem}.tum"))
        messages = log[channel]
        assert trajectory.num_poses == len(messages) > 100
        for k in (0, len(messages) // 2, len(messages) - 1):
            x, y, heading = pose_of(messages[k])
            assert trajectory.timestamps[k] == pytest.approx(messages[k].utime * 1e-6, abs=1e-9)
            assert trajectory.positions_xyz[k].tolist() == [x, y, 0.0]
            w, qx, qy, qz = trajectory.orientations_quat_wxyz[k]
            assert (qx, qy) == (0.0, 0.0)
            assert math.atan2(2 * qz * w, w * w - qz * qz) == pytest.approx(heading, abs=1e-12)
    # No SMOOTHED_POSE in a replay of the estimator: no smoothed.tum.
    assert not (out / "tum" / "smoothed.tum").exists()


def test_smoothed_pose_is_exported_when_present(run, tmp_path):
    from slammtt.lcmlog import LogReader, LogWriter
    log = tmp_path / "with-smoothed.lcm"
    with LogWriter(log) as writer:
        for channel, utime, message in LogReader(run.log):
            writer.write(utime, channel, message.encode())
            if channel == "POSE":
                message.x_m += 0.5
                writer.write(utime, "SMOOTHED_POSE", message.encode())
    err = export_ok(log, "--tum", tmp_path / "tum")
    poses = len(read_log(run.log)["POSE"])
    assert f"smoothed.tum ({poses} poses)" in err
    smoothed = (tmp_path / "tum" / "smoothed.tum").read_text().splitlines()
    estimate = (tmp_path / "tum" / "estimate.tum").read_text().splitlines()
    assert len(smoothed) == poses
    assert float(smoothed[3].split()[1]) == pytest.approx(float(estimate[3].split()[1]) + 0.5)


def read_table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def test_csv_tables_have_units_and_every_row(run, exported):
    out, err = exported
    log = read_log(run.log)
    header, rows = read_table(out / "csv" / "poses.csv")
    assert header[:5] == ["source", "utime_us", "x_m", "y_m", "heading_rad"]
    by_source = {}
    for row in rows:
        by_source.setdefault(row[0], []).append(row)
    assert len(by_source["estimate"]) == len(log["POSE"])
    assert len(by_source["odometry"]) == len(log["ODOMETRY"])
    assert len(by_source["truth"]) == len(log["GROUND_TRUTH"])
    last = log["POSE"][-1]
    assert by_source["estimate"][-1][1:5] == [str(last.utime), repr(last.x_m), repr(last.y_m),
                                              repr(last.heading_rad)]

    header, rows = read_table(out / "csv" / "tracks.csv")
    assert header[:8] == ["utime_us", "id", "class", "confirmed", "x_m", "y_m", "vx_mps",
                          "vy_mps"]
    assert len(rows) == sum(len(m.tracks) for m in log["TRACKS"]) > 0
    assert {row[2] for row in rows} <= {"static", "moving", "undecided"}

    header, rows = read_table(out / "csv" / "map.csv")
    assert header == ["utime_us", "id", "x_m", "y_m", "var_x_m2", "cov_xy_m2", "var_y_m2"]
    final = log["MAP"][-1]
    last_rows = [r for r in rows if r[0] == str(final.utime)]
    assert [(int(r[1]), float(r[2]), float(r[3])) for r in last_rows] == \
        [(l.id, l.x_m, l.y_m) for l in final.landmarks]

    header, rows = read_table(out / "csv" / "features.csv")
    assert "range_m" in header and "bearing_rad" in header
    assert len(rows) == sum(len(m.features) for m in log["FEATURES"])
    for name in ("line_features.csv", "person_features.csv", "truth_objects.csv"):
        header, rows = read_table(out / "csv" / name)
        assert header[0] == "utime_us"
        assert all(len(row) == len(header) for row in rows)
    assert "CSV: poses.csv" in err


def test_same_log_same_bytes(run, exported, tmp_path):
    out, _ = exported
    export_ok(run.log, "--tum", tmp_path / "tum", "--csv", tmp_path / "csv", "--mot",
              tmp_path / "mot", "--config", run.config)
    for sub in ("tum", "csv", "mot"):
        names = sorted(p.relative_to(out / sub) for p in (out / sub).rglob("*") if p.is_file())
        assert names == sorted(p.relative_to(tmp_path / sub)
                               for p in (tmp_path / sub).rglob("*") if p.is_file())
        assert len(names) >= 3
        for name in names:
            assert (out / sub / name).read_bytes() == (tmp_path / sub / name).read_bytes()


def test_a_link_planted_at_an_output_is_replaced_not_written_through(run, tmp_path):
    victim = tmp_path / "victim"
    victim.write_text("keep me")
    (tmp_path / "tum").mkdir()
    (tmp_path / "tum" / "estimate.tum").symlink_to(victim)
    export_ok(run.log, "--tum", tmp_path / "tum")
    assert victim.read_text() == "keep me"
    estimate = tmp_path / "tum" / "estimate.tum"
    assert not estimate.is_symlink() and len(estimate.read_text().splitlines()) > 100
    assert not list((tmp_path / "tum").glob("*.partial*"))


def one_line_error(status, err, expected_status):
    assert status == expected_status, err
    assert len(err.strip().splitlines()) == 1, err
    assert err.startswith("slammtt-export: error: ")


def test_command_line(tmp_path):
    status, out, err = run_export("--help")
    assert status == 0 and "--tum DIR" in out and "--mcap FILE" in out
    status, out, err = run_export("--version")
    assert status == 0 and out.startswith("slammtt-export 0.1.0")
    one_line_error(*run_export(tmp_path / "x.lcm")[::2], 2)            # no output chosen
    one_line_error(*run_export()[::2], 2)
    one_line_error(*run_export("x.lcm", "--tum", tmp_path, "--bogus")[::2], 2)
    one_line_error(*run_export("x.lcm", "--mot", tmp_path, "--mot-box-m", "nan")[::2], 2)
    one_line_error(*run_export("x.lcm", "--tum", tmp_path, "--channel", "POSE")[::2], 2)
    config = tmp_path / "bad.yaml"
    config.write_text("channels:\n  posse: P\n")
    one_line_error(*run_export("x.lcm", "--tum", tmp_path, "-c", config)[::2], 2)
    one_line_error(*run_export(tmp_path / "absent.lcm", "--tum", tmp_path / "t")[::2], 1)
    garbage = tmp_path / "garbage.lcm"
    garbage.write_bytes(b"not a log at all" * 10)
    status, _, err = run_export(garbage, "--tum", tmp_path / "t")
    one_line_error(status, err, 1)
    assert not (tmp_path / "t").exists() or not any((tmp_path / "t").iterdir())


def test_launcher_runs_the_venv_program():
    launcher = BIN_DIR / "slammtt-export"
    if not launcher.exists():
        pytest.skip(f"{launcher} is not written (configure the build)")
    done = subprocess.run([str(launcher), "--version"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0 and done.stdout.startswith("slammtt-export "), done.stderr


def test_mot_files_read_by_trackeval_and_py_motmetrics(run, tmp_path):
    """TrackEval's MOTChallenge reader (MotChallenge2DBox, the folder layout of the export) and
    py-motmetrics' (mot15-2D) read the files: every row, the flags, the points."""
    import motmetrics
    import trackeval
    err = export_ok(run.log, "--mot", tmp_path, "--mot-sequence", "seq", "--config", run.config)
    counts = dict(re.search(r"MOT: (?P<frames>\d+) frames, (?P<truth>\d+) truth rows "
                            r"\((?P<scored>\d+) scored\), (?P<tracks>\d+) track rows", err)
                  .groupdict())
    counts = {k: int(v) for k, v in counts.items()}
    assert counts["truth"] > counts["scored"] > 0 and counts["tracks"] > 0
    dataset = trackeval.datasets.MotChallenge2DBox({
        "GT_FOLDER": str(tmp_path / "gt"), "TRACKERS_FOLDER": str(tmp_path / "trackers"),
        "TRACKERS_TO_EVAL": ["slammtt"], "SKIP_SPLIT_FOL": True, "SEQ_INFO": {"seq": None},
        "PRINT_CONFIG": False})
    raw = dataset.get_raw_seq_data("slammtt", "seq")
    assert raw["num_timesteps"] == counts["frames"]
    assert sum(len(ids) for ids in raw["gt_ids"]) == counts["truth"]
    assert sum(len(ids) for ids in raw["tracker_ids"]) == counts["tracks"]
    # MOTChallenge's preprocessing drops the flag-0 truth (standing or invisible movers).
    data = dataset.get_preprocessed_seq_data(raw, "pedestrian")
    assert data["num_gt_dets"] == counts["scored"]
    assert data["num_tracker_dets"] == counts["tracks"]

    gt = motmetrics.io.loadtxt(str(tmp_path / "gt" / "seq" / "gt" / "gt.txt"), fmt="mot15-2D")
    tracks = motmetrics.io.loadtxt(str(tmp_path / "trackers" / "slammtt" / "data" / "seq.txt"),
                                   fmt="mot15-2D")
    assert len(gt) == counts["truth"] and int((gt["Confidence"] == 1).sum()) == counts["scored"]
    assert len(tracks) == counts["tracks"]
    # The truth points: (X, Y) + 1 (the reader's 1-based pixel shift) + half the 1 m box.
    log = read_log(run.log)
    frames = [line.split(",") for line in (tmp_path / "frames.csv").read_text().splitlines()[1:]]
    utime_of = {int(f): int(u) for f, u in frames}
    truth_at = {m.utime: m for m in log["GROUND_TRUTH"]}
    (frame, object_id), row = next(iter(gt.iterrows()))
    o = next(o for o in truth_at[utime_of[frame]].objects if o.id == object_id)
    assert row["X"] + 1 + 0.5 == pytest.approx(o.x_m, abs=1e-9)
    assert row["Y"] + 1 + 0.5 == pytest.approx(o.y_m, abs=1e-9)


def test_mot_tracks_are_the_reported_ones_as_slammtt_eval_scores(run, tmp_path):
    """The track rows are the tracks slammtt-eval scores: reported (measured within the
    reporting time) and moving; a confirmed track that coasts is not one of them."""
    export_ok(run.log, "--mot", tmp_path, "--mot-sequence", "seq", "--config", run.config)
    frames = [line.split(",") for line in (tmp_path / "frames.csv").read_text().splitlines()[1:]]
    frame_of = {int(u): int(f) for f, u in frames}
    log = read_log(run.log)
    reported, coasting = set(), 0
    for m in log["TRACKS"]:
        if m.utime not in frame_of:
            continue
        for t in m.tracks:
            if t.object_class != 1:
                continue
            if t.reported:
                reported.add((frame_of[m.utime], t.id))
            elif t.confirmed:
                coasting += 1
    rows = (tmp_path / "trackers" / "slammtt" / "data" / "seq.txt").read_text().splitlines()
    written = {(int(r.split(",")[0]), int(r.split(",")[1])) for r in rows}
    assert coasting > 0, "the run has no coasting confirmed mover: nothing to tell apart"
    assert written == reported and len(rows) == len(reported)
