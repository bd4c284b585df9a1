"""Agreement of slammtt-eval's figures with the reference libraries where the definitions
coincide (docs/evaluation.md, "Agreement with the reference libraries"):

- MOTA, identity switches, misses, false positives and IDF1 against py-motmetrics, reading the
  MOTChallenge files of slammtt-export (distance: Euclidean on the box corners, which are the
  points shifted by half the box side);
- HOTA, DetA, AssA, LocA against TrackEval's HOTA class, and MOTA and IDF1 against its CLEAR and
  Identity classes, on the same files;
- aligned ATE and RPE against evo (evo_ape -a, evo_rpe) on shipped scenarios' logs.

The tracking logs are built here: movers that are always visible and walking (no don't-care
rule of slammtt-eval applies) and far apart (every truth has at most one track within the 1 m
threshold, so every matching is unique and the libraries' different tie-breaks and distance
powers cannot differ). Seeds 1-6 draw the scenes; every seed must agree.

py-motmetrics does not keep matches the way slammtt-eval does: it keeps an object's last track
even when that track has since been matched to another object (the stale mapping below).
"""

import math
import subprocess

import numpy as np
import pytest

from conftest import EVAL, evo_stats, export_ok, scenario_run

# py-motmetrics 1.4.0's reader warns on pandas 3 (motmetrics/io.py subtracts a tuple).
pytestmark = pytest.mark.filterwarnings("ignore:Operation with tuple is deprecated")

THRESHOLD_M = 1.0
PERIOD_US = 100000
START_US = 1700000000000000


def tracking_log(path, frames):
    """A log of GROUND_TRUTH, POSE and TRACKS at 10 Hz: `frames` is a list of (truth, tracks),
    each a list of (id, x_m, y_m). The robot stands at the world origin and its estimate is
    exact (the anchoring is the identity); every truth is a visible walking disc, every track a
    confirmed mover."""
    from slammtt.lcmlog import LogWriter
    from slammtt_msgs import ground_truth_t, object_truth_t, pose_t, track_t, tracks_t
    with LogWriter(path) as writer:
        for k, (truth, tracks) in enumerate(frames):
            utime = START_US + k * PERIOD_US
            g = ground_truth_t()
            g.utime = utime
            for object_id, x_m, y_m in truth:
                o = object_truth_t()
                o.id, o.x_m, o.y_m, o.vx_mps, o.vy_mps = object_id, x_m, y_m, 1.0, 0.0
                o.radius_m, o.object_class, o.kind, o.parent_id = 0.2, 1, 4, -1
                o.beams_on_object, o.visible = 10, True
                g.objects.append(o)
            g.num_objects = len(g.objects)
            pose = pose_t()
            pose.utime = utime
            t = tracks_t()
            t.utime = utime
            for track_id, x_m, y_m in tracks:
                track = track_t()
                track.id, track.x_m, track.y_m, track.vx_mps = track_id, x_m, y_m, 1.0
                track.covariance = [0.01 if i % 5 == 0 else 0.0 for i in range(16)]
                track.object_class, track.confirmed, track.hits = 1, True, 5
                # Measured in this scan, so a reported track (docs/evaluation.md).
                track.measured, track.coasting_s, track.reported = True, 0.0, True
                track.first_seen_utime = track.last_seen_utime = utime
                t.tracks.append(track)
            t.num_tracks = len(t.tracks)
            writer.write(utime, "GROUND_TRUTH", g)
            writer.write(utime, "POSE", pose)
            writer.write(utime, "TRACKS", t)


def random_scene(seed, frames=60):
    """Four movers on parallel lanes 4 m apart; their tracks with noise (under 0.6 m), gaps,
    one identity change, one excursion beyond the threshold, a false track far from
    everything, a mover that enters late and one that leaves early."""
    rng = np.random.default_rng(seed)
    lanes = [(i, 4.0 * i) for i in range(1, 5)]
    exists = {1: range(frames), 2: range(frames), 3: range(rng.integers(5, 20), frames),
              4: range(0, rng.integers(35, 55))}
    gap = set(range(*sorted(rng.integers(5, 55, 2))))
    switch_at = int(rng.integers(10, 50))
    excursion_from = int(rng.integers(5, 50))
    excursion = set(range(excursion_from, excursion_from + int(rng.integers(2, 6))))
    out = []
    for k in range(frames):
        truth, tracks = [], []
        for object_id, y in lanes:
            if k not in exists[object_id]:
                continue
            x = -6.0 + 0.1 * k + 0.3 * object_id
            truth.append((object_id, x, y))
            if object_id == 1 and k in gap:
                continue
            noise = np.clip(rng.normal(0.0, 0.15, 2), -0.4, 0.4)
            track_id = 10 + object_id
            if object_id == 2 and k >= switch_at:
                track_id = 30
            if object_id == 3 and k in excursion:
                noise = noise + np.array([0.0, 1.5])
            tracks.append((track_id, x + noise[0], y + noise[1]))
        if rng.random() < 0.3:
            tracks.append((99, 0.0, -30.0 + rng.normal()))
        out.append((truth, tracks))
    return out


def evaluate(log, tmp_path):
    """slammtt-eval's tracking figures of a log."""
    import json
    if not EVAL.exists():
        pytest.skip(f"{EVAL} is not built: the agreement tests are skipped")
    report = tmp_path / "report.json"
    done = subprocess.run([str(EVAL), str(log), "--json", str(report)], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    report = json.loads(report.read_text())
    tracking = report["detail"]["tracking"]
    assert tracking["clear_mot"]["dont_care"] == 0      # the definitions coincide
    return report, tracking


def mot_files(log, tmp_path):
    out = tmp_path / "mot"
    export_ok(log, "--mot", out, "--mot-sequence", "seq")
    return out / "gt" / "seq" / "gt" / "gt.txt", out / "trackers" / "slammtt" / "data" / "seq.txt"


def motmetrics_summary(gt_path, tracks_path):
    """py-motmetrics on the exported files: the truth rows MOTChallenge scores (flag 1), the
    distance Euclidean on (X, Y) = (bb_left, bb_top) within 1 m (its 'euc' compares squared
    distances, so distth is 1 m^2)."""
    import motmetrics as mm
    gt = mm.io.loadtxt(str(gt_path), fmt="mot15-2D", min_confidence=1)
    tracks = mm.io.loadtxt(str(tracks_path), fmt="mot15-2D")
    accumulator = mm.utils.compare_to_groundtruth(gt, tracks, "euc", distfields=["X", "Y"],
                                                  distth=THRESHOLD_M ** 2)
    metrics = ["mota", "idf1", "num_switches", "num_misses", "num_false_positives",
               "num_objects", "num_matches", "idtp"]
    summary = mm.metrics.create().compute(accumulator, metrics=metrics, name="seq")
    return {k: summary[k]["seq"] for k in metrics}


def trackeval_data(gt_path, tracks_path, similarity_of_distance):
    """The data dict TrackEval's metrics take, from the exported files: ids renumbered from 0,
    similarity of every (truth, track) pair of a frame from their distance."""
    def rows(path, flag_column=None):
        by_frame = {}
        for line in open(path):
            v = line.strip().split(",")
            if flag_column is not None and float(v[flag_column]) != 1:
                continue
            by_frame.setdefault(int(v[0]), []).append((int(v[1]), float(v[2]), float(v[3])))
        return by_frame
    gt, tracks = rows(gt_path, flag_column=6), rows(tracks_path)
    frames = range(1, max([*gt, *tracks]) + 1)
    gt_ids = {i: n for n, i in enumerate(sorted({r[0] for f in gt.values() for r in f}))}
    track_ids = {i: n for n, i in enumerate(sorted({r[0] for f in tracks.values() for r in f}))}
    data = {"num_timesteps": len(frames), "num_gt_ids": len(gt_ids),
            "num_tracker_ids": len(track_ids), "gt_ids": [], "tracker_ids": [],
            "similarity_scores": [], "num_gt_dets": 0, "num_tracker_dets": 0}
    for f in frames:
        g, t = gt.get(f, []), tracks.get(f, [])
        data["gt_ids"].append(np.array([gt_ids[r[0]] for r in g], dtype=int))
        data["tracker_ids"].append(np.array([track_ids[r[0]] for r in t], dtype=int))
        data["similarity_scores"].append(np.array(
            [[similarity_of_distance(math.hypot(a[1] - b[1], a[2] - b[2])) for b in t]
             for a in g]).reshape(len(g), len(t)))
        data["num_gt_dets"] += len(g)
        data["num_tracker_dets"] += len(t)
    return data


def trackeval_metrics(gt_path, tracks_path):
    from trackeval.metrics import CLEAR, HOTA, Identity
    # HOTA: slammtt-eval's similarity S = max(0, 1 - d / threshold).
    hota = HOTA().eval_sequence(trackeval_data(
        gt_path, tracks_path, lambda d: max(0.0, 1.0 - d / THRESHOLD_M)))
    # CLEAR and Identity match when similarity >= 0.5: S' = 1 - d / (2 threshold) puts that at
    # d <= threshold.
    half = trackeval_data(gt_path, tracks_path, lambda d: max(0.0, 1.0 - d / (2 * THRESHOLD_M)))
    config = {"THRESHOLD": 0.5, "PRINT_CONFIG": False}
    return hota, CLEAR(config).eval_sequence(half), Identity(config).eval_sequence(half)


@pytest.mark.parametrize("seed", [1, 2, 3, 4, 5, 6])
def test_tracking_figures_equal_py_motmetrics_and_trackeval(seed, tmp_path):
    log = tmp_path / "scene.lcm"
    tracking_log(log, random_scene(seed))
    report, tracking = evaluate(log, tmp_path)
    clear_mot = tracking["clear_mot"]
    identity = tracking["identity"]
    gt_path, tracks_path = mot_files(log, tmp_path)

    mm = motmetrics_summary(gt_path, tracks_path)
    assert clear_mot["truth"] == mm["num_objects"]
    # (py-motmetrics counts a match that is an identity switch as a switch, not a match)
    assert clear_mot["matches"] == mm["num_matches"] + mm["num_switches"]
    assert clear_mot["misses"] == mm["num_misses"] > 0
    assert clear_mot["false_positives"] == mm["num_false_positives"] > 0
    assert clear_mot["id_switches"] == mm["num_switches"] >= 1
    assert report["mota"] == pytest.approx(mm["mota"], abs=1e-12)
    assert identity["id_true_positives"] == mm["idtp"]
    assert report["idf1"] == pytest.approx(mm["idf1"], abs=1e-12)

    hota, clear, ident = trackeval_metrics(gt_path, tracks_path)
    assert report["hota"] == pytest.approx(float(np.mean(hota["HOTA"])), abs=1e-9)
    assert identity["det_a"] == pytest.approx(float(np.mean(hota["DetA"])), abs=1e-9)
    assert identity["ass_a"] == pytest.approx(float(np.mean(hota["AssA"])), abs=1e-9)
    assert identity["loc_a"] == pytest.approx(float(np.mean(hota["LocA"])), abs=1e-9)
    assert 0.3 < report["hota"] < 0.95
    assert report["mota"] == pytest.approx(clear["MOTA"], abs=1e-12)
    assert clear_mot["id_switches"] == clear["IDSW"]
    assert report["idf1"] == pytest.approx(ident["IDF1"], abs=1e-12)


STALE_MAPPING = [
    # frame 1: truth A (id 1) and track X (id 10) match.
    ([(1, 0.0, 0.0)], [(10, 0.0, 0.0)]),
    # frame 2: A is gone; X is on truth B (id 2) and matches it.
    ([(2, 1.2, 0.0)], [(10, 1.2, 0.0)]),
    # frame 3: A is back; X lies 0.6 m from both A and B; track Y (id 11) 0.5 m from A only.
    ([(1, 0.0, 0.0), (2, 1.2, 0.0)], [(10, 0.6, 0.0), (11, 0.0, 0.5)]),
]


def test_py_motmetrics_keeps_a_stale_mapping(tmp_path):
    """In frame 3, slammtt-eval keeps B with X (B's last match, which no other object has had
    since) and gives A the other track Y, an identity switch: 1 error in 4 truths, MOTA 0.75.
    py-motmetrics keeps A with X, A's match of frame 1, although X has been B's since (mot.py,
    step 1 of MOTAccumulator.update: `self.m[o]` is never cleared when its track goes to
    another object), so B finds no track within 1 m: a miss and a false positive, MOTA 0.5,
    and one pair fewer matched. Its answer depends on the order of the truth rows of the
    frame: with B's row first, B keeps X, and py-motmetrics agrees with slammtt-eval.
    TrackEval's CLEAR (which keeps matches of the previous frame only) agrees with
    slammtt-eval."""
    log = tmp_path / "stale.lcm"
    tracking_log(log, STALE_MAPPING)
    report, tracking = evaluate(log, tmp_path)
    clear_mot = tracking["clear_mot"]
    assert (clear_mot["truth"], clear_mot["matches"], clear_mot["misses"],
            clear_mot["false_positives"], clear_mot["id_switches"]) == (4, 4, 0, 0, 1)
    assert report["mota"] == pytest.approx(0.75)
    event = tracking["identity_switch_events"][0]
    assert (event["truth_id"], event["previous_track_id"], event["new_track_id"]) == (1, 10, 11)

    gt_path, tracks_path = mot_files(log, tmp_path)
    mm = motmetrics_summary(gt_path, tracks_path)
    assert (mm["num_matches"], mm["num_misses"], mm["num_false_positives"],
            mm["num_switches"]) == (3, 1, 1, 0)
    assert mm["mota"] == pytest.approx(0.5)
    _, clear, _ = trackeval_metrics(gt_path, tracks_path)
    assert clear["MOTA"] == pytest.approx(0.75) and clear["IDSW"] == 1

    # The same scene with B's row before A's in frame 3: py-motmetrics now agrees.
    swapped = STALE_MAPPING[:2] + [(STALE_MAPPING[2][0][::-1], STALE_MAPPING[2][1])]
    log = tmp_path / "swapped.lcm"
    tracking_log(log, swapped)
    report, _ = evaluate(log, tmp_path)
    assert report["mota"] == pytest.approx(0.75)
    mm = motmetrics_summary(*mot_files(log, tmp_path / "swapped"))
    assert mm["mota"] == pytest.approx(0.75) and mm["num_switches"] == 1


@pytest.fixture(scope="module", params=[("s1-crossing", 7), ("s2-lobby", 3)],
                ids=lambda p: f"{p[0]}-seed{p[1]}")
def run(request, tmp_path_factory):
    return scenario_run(tmp_path_factory, *request.param)


def test_aligned_ate_and_rpe_equal_evos(run, tmp_path):
    export_ok(run.log, "--tum", tmp_path / "tum")
    truth, estimate = tmp_path / "tum" / "truth.tum", tmp_path / "tum" / "estimate.tum"
    robot = run.report["detail"]["robot"]
    aligned = evo_stats("evo_ape", "tum", truth, estimate, "-a", home=tmp_path)
    assert aligned["rmse"] == pytest.approx(robot["aligned"]["ate_rmse_m"], abs=1e-6)
    assert aligned["max"] == pytest.approx(robot["aligned"]["ate_max_m"], abs=1e-6)
    assert aligned["rmse"] < run.report["ate_rmse_m"]
    rpe = evo_stats("evo_rpe", "tum", truth, estimate, home=tmp_path)
    assert rpe["rmse"] == pytest.approx(robot["rpe"]["translation_rmse_m"], abs=1e-6)
    assert rpe["max"] == pytest.approx(robot["rpe"]["translation_max_m"], abs=1e-6)
    assert rpe["mean"] == pytest.approx(robot["rpe"]["translation_mean_m"], abs=1e-6)
    rotation = evo_stats("evo_rpe", "tum", truth, estimate, "-r", "angle_rad", home=tmp_path)
    assert rotation["rmse"] == pytest.approx(robot["rpe"]["rotation_rmse_rad"], abs=1e-6)
