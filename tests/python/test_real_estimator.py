"""The estimator on the real recordings of ../shared/data/real (issue 13, "Real recordings"): no
ground truth, so the figures of scripts/measure-real.py are reported in docs/targets.md and kept
here as REGRESSION FLOORS: each is the figure measured when this file was written, made a few
percent worse (5 %, in the direction that is worse). They are not the issue's aims (negative_2:
0 people per minute) and a failing floor says that the estimator got worse on real data, not
that a target was missed. Better figures pass; move the floor with them.

The script runs on the whole recordings (every scan: about 20 s on a loaded 2-core machine).
Skipped, with the reason, without ../shared/data/real or without the built programs. The
definitions are tested first on made-up data (always run)."""

import importlib.util
import json
import math
import statistics
import subprocess
import sys

import numpy as np
import pytest

from slammtt import recording_figures as figures
from slammtt_msgs import (features_t, laser_scan_t, line_feature_t, person_feature_t,
                          track_t, tracks_t)

from conftest import BIN_DIR, SHARED_REAL, SOURCE_DIR

SCRIPT = SOURCE_DIR / "scripts" / "measure-real.py"
WORSE = 1.05     # a floor is the measured figure made 5 % worse

# Measured figures (scripts/measure-real.py, docs/targets.md), per recording, in the "sensor"
# configuration (the import's mount file plus the scanner's field of view and range). Since the
# estimator takes the geometry its configuration does not give from the log's LASER_GEOMETRY
# (docs/estimator.md, "Laser geometry"), the "mount" configuration (the mount file alone, as
# the README runs it) gives the same estimate: test_the_mount_file_alone_gives_the_sensors_
# estimate asserts it. Lower is better for *_per_minute, *_spread_m and *_rms_m; higher is
# better for match_pairs and map_line_share.
# Neither real people recording has ODOMETRY: since the robot moves by the alignment of
# consecutive scans (docs/estimator.md, "Motion without odometry"), negative_2 went from 58.1 to
# 42.6 identities per minute and the demo's agreement with the leg pairs from 0.318 to 0.360,
# while the demo's identities went from 17.6 to 19.0 per minute (its still scanner's estimated
# pose wanders about as much as before: median 1.5 cm against 1.0 cm, at most 9.5 cm and 4.3
# degrees against 12.1 cm and 3.3 degrees).
# Perception's surface-piece rule and its 0.7 m leg pairing (docs/perception.md) then moved, with
# the alignment: negative_2 42.6 -> 44.6 identities per minute, the demo 19.0 -> 18.1 per minute
# and its agreement with the leg pairs 0.360 -> 0.316. Then lines_point_on_line_m 0.1 -> 0.25
# (a point feature within 0.25 m of a wall is a piece of it): negative_2 44.6 -> 29.1, the demo
# 18.1 and 0.316 -> 0.355; Mines spread 0.0968 -> 0.0951 (exp1) and 0.0907 -> 0.0935 m (exp2),
# wall points to the estimator's own final lines 0.0797 -> 0.0650 and 0.0771 -> 0.0716 m.
# Then perception's leg-like clusters within 0.025 m of a line of the scan became pieces of it
# (docs/perception.md; 0.06 of 10.6 point features and 0.03 of 2.2 person features per Mines
# scan fewer): negative_2 29.1 -> 27.0, the demo unchanged (18.1, 0.355); Mines exp1 spread
# 0.0951 -> 0.0933 m, RMS to the final lines 0.0650 -> 0.0610 m, share 0.983 -> 0.974; exp2
# spread 0.0935 -> 0.1005 m, RMS 0.0716 -> 0.0744 m, share 0.984 -> 0.973 (one recording
# better, the other worse, from a change of 0.6 % of the point features: the estimate's
# sensitivity, not a rule that places Mines walls worse).
# Then the reporting of movers by their recent scans (docs/targets.md, "People: reporting of
# movers by their recent scans"): the demo's agreement with the leg pairs 0.355 -> 0.398; the
# other figures unchanged (reporting does not change the estimate).
# Then, together (the merged stationary anchor, points behind walls, the alignment's short lines
# and the reporting rule; each measured alone in docs/targets.md): negative_2 27.0 -> 25.9, the demo
# 18.1 -> 14.8 per minute, its agreement with the leg pairs 0.398 -> 0.332 (0.355 before all of
# them); Mines exp1 spread 0.0933 -> 0.0955 m, RMS 0.0610 -> 0.0607 m, share 0.974 -> 0.977;
# exp2 spread 0.1005 -> 0.1020 m (raw odometry 0.0980: open), RMS 0.0744 -> 0.0814 m, share
# 0.973 -> 0.972. Floors at these figures; the exp2 regression is listed in docs/targets.md.
# (The anchor was then off by default for a while, with the window's hold-back: negative_2 27.0,
# the demo 17.1 and 0.352, exp1 0.0944 / 0.0600 / 0.977, exp2 0.1000 / 0.0769 / 0.976; on again
# with the window's births blocked inside held-back gates, branch wt-s1: the figures above, measured
# again by scripts/measure-real.py.)
# Then people confirmed by 2 of their last 5 scans (tracks_confirm_person_hits 3 -> 2, docs/
# targets.md "People: confirmed by two scans"), the alignment's filtered velocity and the
# smoother's between-keyframe sightings, merged, with the stationary anchor off by default (on,
# it cost the large loop's smoothed map): negative_2 27.0 -> 25.9 (25 identities in 0.96 min),
# the demo 17.1 -> 18.1 per minute and its agreement with the leg pairs 0.352 -> 0.384; Mines
# exp1 spread 0.0944 -> 0.0936 m, RMS 0.0600 -> 0.0586 m, share 0.977 -> 0.978; exp2 spread
# 0.1000 -> 0.0975 m (sharper than raw odometry's 0.0980 again), RMS 0.0769 -> 0.0835 m, share
# 0.976 -> 0.977. (With the anchor on: 32.2, 17.1 and 0.421, exp1 0.0928 / 0.0652 / 0.977, exp2
# 0.0891 / 0.0748 / 0.975.) Measured by scripts/measure-real.py on the merge.
# Until then each floor was one run's figure. One run's figure does not say how the method does
# on the recording: with the estimator's floors of a line feature's sigmas 1 % higher or lower
# (lines_min_rho_sigma_m 0.03 -> 0.0303 / 0.0297, lines_min_alpha_sigma_deg 1 -> 1.01 / 0.99),
# the figures above moved to: the demo 16.2-19.0 identities per minute and 0.339-0.398
# agreement, Mines exp1 spread 0.0919-0.0991 m and RMS 0.0586-0.0697 m, exp2 spread
# 0.0869-0.1144 m and RMS 0.0768-0.0835 m (negative_2 25.9-27.0): as far as the changes of the
# method recorded above moved them (e.g. the Mines exp2 spread 0.1005 -> 0.1020 -> 0.0975 m).
# So the floors are now each figure's median
# over five runs, the shipped configuration and those four (scripts/measure-real.py
# --perturbed, `sensor_median`), measured on main at a505322 (the figures above in brackets: one
# run's; the old floor constant for the demo's agreement was 0.384, the run's 0.38498), made 5 %
# worse as before: negative_2 25.9 (25.9), the demo 18.1 (18.1) and 0.379 (0.385), exp1 0.0963
# (0.0936) / 0.0614 (0.0586) / 0.978 (0.978), exp2 0.0965 (0.0975) / 0.0784 (0.0835) / 0.974
# (0.977): four looser, two tighter. docs/targets.md, "Real recordings: one run against five".
# Then a walker's take-over of the standing person it was (people_taken_over_within_m 0.5, on):
# medians exp1 0.0988 / 0.0631 / 0.979 (within these floors, not within the old one-run ones),
# exp2 0.0975 / 0.0791 / 0.974, the demo 18.1 and 0.385, negative_2 25.9.
# Then a person track more than 6 m from the robot is reported from its 6th hit
# (people_report_far_m, people_report_far_min_hits; reporting only): negative_2 25.9 -> 18.7 (18
# identities in 0.96 min, each of the five runs), every other median as before.
MEASURED = {
    ("negative_2", "sensor_median"): {"person_identities_per_minute": 18.7},
    ("leg_tracker_demo", "sensor_median"): {"person_identities_per_minute": 18.1,
                                            "match_pairs": 0.379},
    ("mines_exp1", "sensor_median"): {"wall_spread_m": 0.0963, "map_line_rms_m": 0.0614,
                                      "map_line_share": 0.978},
    ("mines_exp2", "sensor_median"): {"wall_spread_m": 0.0965, "map_line_rms_m": 0.0784,
                                      "map_line_share": 0.974},
}
HIGHER_IS_BETTER = {"match_pairs", "map_line_share"}


# ---- the definitions, on made-up data ----

def scan(angles_rad, ranges_m, valid=None, utime=0):
    m = laser_scan_t()
    m.utime = utime
    m.num_beams = len(angles_rad)
    m.angle_rad, m.range_m = list(angles_rad), list(ranges_m)
    m.intensity = [1.0] * m.num_beams
    m.valid = list(valid) if valid is not None else [True] * m.num_beams
    m.range_max_m = 10.0
    return m


def test_spread_of_points_about_a_line_is_their_offset_rms():
    rng = np.random.default_rng(3)
    along = rng.uniform(0.01, 0.99, 4000)
    offset = rng.normal(0.0, 0.02, 4000)
    # A wall at 30 degrees through one 1 m cell: the spread is the offsets' RMS, whatever the
    # wall's direction.
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    points = np.stack([0.2 + 0.5 * along * c - offset * s, 0.2 + 0.5 * along * s + offset * c],
                      axis=1)
    spread, used = figures.cell_line_spread(points, cell_m=1.0, min_points=20)
    assert used == 4000
    assert spread == pytest.approx(math.sqrt(np.mean(offset ** 2)), rel=0.02)
    # The same wall seen twice, 0.2 m apart (a blurred map): about 0.1 m.
    ghost = points + np.array([-0.1 * s, 0.1 * c])
    spread, _ = figures.cell_line_spread(np.concatenate([points - [-0.1 * s, 0.1 * c], ghost]),
                                         cell_m=10.0)
    assert spread == pytest.approx(math.hypot(0.1, 0.02), rel=0.05)
    # Cells with fewer points than asked are left out.
    assert figures.cell_line_spread(points[:10], min_points=20) == (pytest.approx(math.nan,
                                                                                nan_ok=True), 0)


def test_beams_are_placed_by_the_pose_and_the_mount():
    beams = scan([0.0, math.pi / 2, 1.0], [1.0, 2.0, 3.0], valid=[True, True, False])
    trajectory = np.array([[1.0, 2.0, math.pi / 2]])
    points = figures.scan_points([beams], trajectory, (0.145, 0.0, 0.0))
    assert points == pytest.approx(np.array([[1.0, 3.145], [-1.0, 2.145]]))
    # A laser turned by 90 degrees sees ahead what its beam at 0 sees; a mask picks beams.
    points = figures.scan_points([beams], np.zeros((1, 3)), (0.0, 0.0, math.pi / 2),
                                 masks=[np.array([True, False, False])])
    assert points == pytest.approx(np.array([[0.0, 1.0]]))


def test_wall_beams_are_the_beams_on_a_line_feature_inside_its_extent():
    # A wall 2 m ahead from y = -1 to y = 1; beams at y = 0 and 0.5 (on it), y = 1.5 (on its
    # line, beyond its extent), a beam 0.3 m short of it, and an invalid one.
    angles = [0.0, math.atan2(0.5, 2), math.atan2(1.5, 2), 0.1, 0.0]
    ranges = [2.0, math.hypot(2, 0.5), math.hypot(2, 1.5), 1.7, 2.0]
    line = line_feature_t()
    line.rho_m, line.alpha_rad = 2.0, 0.0
    line.first_x_m, line.first_y_m, line.last_x_m, line.last_y_m = 2.0, -1.0, 2.0, 1.0
    f = features_t()
    f.num_lines, f.lines = 1, [line]
    mask = figures.wall_beams(scan(angles, ranges, valid=[True] * 4 + [False]), f)
    assert mask.tolist() == [True, True, False, False, False]


def test_trajectory_is_interpolated_across_the_heading_wrap():
    class Pose:
        def __init__(self, utime, x, heading):
            self.utime, self.x_m, self.y_m, self.heading_rad = utime, x, 0.0, heading
    poses = [Pose(0, 0.0, math.pi - 0.1), Pose(10, 1.0, -math.pi + 0.1)]
    at = figures.trajectory_at(poses, [5, 20])
    assert at[0] == pytest.approx([0.5, 0.0, math.pi])
    assert at[1] == pytest.approx([1.0, 0.0, math.pi + 0.1])     # held at the end
    with pytest.raises(ValueError):
        figures.trajectory_at([poses[1], poses[0]], [5])


def tracks(utime, people):
    """A TRACKS message: (id, reported, kind) per track."""
    m = tracks_t()
    m.utime = utime
    m.tracks = []
    for track_id, reported, kind in people:
        t = track_t()
        t.id, t.reported, t.confirmed, t.kind = track_id, reported, reported, kind
        m.tracks.append(t)
    m.num_tracks = len(m.tracks)
    return m


def features(utime, legs_per_person):
    m = features_t()
    m.utime = utime
    m.people = []
    for legs in legs_per_person:
        p = person_feature_t()
        p.num_legs = legs
        p.leg_index = [0, 1 if legs == 2 else -1]
        m.people.append(p)
    m.num_people = len(m.people)
    return m


def test_person_identities_and_count_agreement():
    person, other = figures.KIND_PERSON, 0
    messages = [tracks(0, [(1, True, person), (2, False, person), (3, True, other)]),
                tracks(30_000_000, [(1, True, person), (4, True, person)]),
                tracks(60_000_000, [])]
    # Ids 1 and 4 were reported people (2 was not reported, 3 is not a person); one minute.
    assert figures.person_identities_per_minute(messages) == (2, pytest.approx(2.0))
    agreement = figures.count_agreement(messages, [features(0, [2]), features(30_000_000, [2, 1]),
                                                   features(60_000_000, [1])])
    # Reported people 1, 2, 0; leg pairs 1, 1, 0; person features 1, 2, 1.
    assert agreement["scans"] == 3
    assert agreement["match_pairs"] == pytest.approx(2 / 3)
    assert agreement["match_person_features"] == pytest.approx(2 / 3)
    assert agreement["mean_reported"] == pytest.approx(1.0)
    with pytest.raises(ValueError):
        figures.count_agreement(messages, [features(1, [2])])


def measure_real_module():
    spec = importlib.util.spec_from_file_location("measure_real", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_median_figures_takes_each_figures_median_through_nested_records():
    median_figures = measure_real_module().median_figures
    runs = [{"a": 3, "b": {"c": 0.1, "d": 7}}, {"a": 1, "b": {"c": 0.5, "d": 7}},
            {"a": 2, "b": {"c": 0.3, "d": 9}}, {"a": 9, "b": {"c": 0.2, "d": 8}},
            {"a": 5, "b": {"c": 0.4, "d": 7}}]
    assert median_figures(runs) == {"a": 3, "b": {"c": 0.3, "d": 7}}
    # A figure that some run could not measure (NaN) has no median, whatever the order.
    runs[2]["b"]["c"] = math.nan
    assert math.isnan(median_figures(runs)["b"]["c"])
    assert math.isnan(median_figures(runs[::-1])["b"]["c"])


def test_perturbed_runs_move_each_noise_floor_one_percent_either_way():
    module = measure_real_module()
    defaults = {"lines_min_rho_sigma_m": 0.03, "lines_min_alpha_sigma_deg": 1.0}
    runs = module.perturbations(["segmenter.x=1", "lines_min_alpha_sigma_deg=2"], defaults)
    assert len(runs) == 4
    assert all(run[:2] == ["segmenter.x=1", "lines_min_alpha_sigma_deg=2"] for run in runs)
    extra = [run[2].split("=") for run in runs]
    assert [name for name, _ in extra] == ["lines_min_rho_sigma_m"] * 2 + \
        ["lines_min_alpha_sigma_deg"] * 2
    assert [float(v) for _, v in extra] == pytest.approx([0.0303, 0.0297, 2.02, 1.98])


# ---- the real recordings: regression floors ----

@pytest.fixture(scope="module")
def measured(tmp_path_factory):
    if not SHARED_REAL.is_dir():
        pytest.skip(f"real recordings absent ({SHARED_REAL}): the tests on them are skipped")
    for program in ("slammtt-import", "slammtt-replay"):
        if not (BIN_DIR / program).exists():
            pytest.skip(f"{BIN_DIR / program} is not built: the tests on real recordings are "
                        "skipped")
    out = tmp_path_factory.mktemp("measure-real")
    done = subprocess.run([sys.executable, str(SCRIPT), str(out), "--bin", str(BIN_DIR),
                           "--real", str(SHARED_REAL), "--perturbed"], capture_output=True,
                          text=True, timeout=900)
    assert done.returncode == 0, done.stderr
    assert "| leg_tracker_demo | sensor |" in done.stdout      # the table is printed
    assert "| leg_tracker_demo | sensor_median |" in done.stdout
    return json.loads((out / "real.json").read_text())


def figure_of(results, recording, config, name):
    figure = results[recording][config]
    return figure[name] if name in figure else figure["estimate"][name]


@pytest.mark.parametrize("recording, config, name",
                         [(r, c, n) for (r, c), names in MEASURED.items() for n in names])
def test_figure_is_no_worse_than_its_floor(shared_real, measured, recording, config, name):
    value = figure_of(measured, recording, config, name)
    was = MEASURED[(recording, config)][name]
    if name in HIGHER_IS_BETTER:
        assert value >= was / WORSE, f"{recording} {config} {name}: {value} (was {was})"
    else:
        assert value <= was * WORSE, f"{recording} {config} {name}: {value} (was {was})"


def test_every_scan_is_measured(shared_real, measured):
    # The demo bag's 1265 scans and negative_2's 435 over their whole length (BAGS.md).
    demo = measured["leg_tracker_demo"]["sensor"]
    assert demo["scans"] == 1265 and demo["minutes"] == pytest.approx(126.0 / 60, abs=0.01)
    assert measured["negative_2"]["sensor"]["scans"] == 435
    # The odometry placement does not depend on the estimator: the same wall points and spread
    # in both configurations (their distance to the MAP lines does); the map has lines.
    for name in ("mines_exp1", "mines_exp2"):
        mount, sensor = measured[name]["mount"], measured[name]["sensor"]
        for key in ("wall_points", "wall_spread_m", "occupied_cells"):
            assert mount["odometry"][key] == sensor["odometry"][key]
        assert sensor["estimate"]["wall_points"] == sensor["odometry"]["wall_points"] > 50000
        assert sensor["map_lines"] > 10


def test_the_median_is_over_five_runs_of_which_one_is_the_shipped_configuration(shared_real,
                                                                                 measured):
    for recording in ("negative_2", "leg_tracker_demo", "mines_exp1", "mines_exp2"):
        runs = measured[recording]["sensor_runs"]
        assert len(runs) == 5 and runs[0] == measured[recording]["sensor"], recording
        median = measured[recording]["sensor_median"]
        if recording.startswith("mines"):
            values = [run["estimate"]["wall_spread_m"] for run in runs]
            assert median["estimate"]["wall_spread_m"] == statistics.median(values)
        else:
            values = [run["person_identities_per_minute"] for run in runs]
            assert median["person_identities_per_minute"] == statistics.median(values)
    # The perturbed runs are other runs: somewhere a figure differs from the shipped one's.
    demo = measured["leg_tracker_demo"]["sensor_runs"]
    assert any(run["match_pairs"] != demo[0]["match_pairs"] for run in demo[1:])


def test_the_mount_file_alone_gives_the_sensors_estimate(shared_real, measured):
    """The import's mount file gives only the mount; the field of view and range come from the
    imported log's LASER_GEOMETRY, so every figure equals the one with them written out (before
    the estimator read LASER_GEOMETRY it kept a 360-degree, 30 m view: 60.2 identities per
    minute on negative_2, 27.6 on the demo bag)."""
    for recording in ("negative_2", "leg_tracker_demo", "mines_exp1", "mines_exp2"):
        assert measured[recording]["mount"] == measured[recording]["sensor"], recording
