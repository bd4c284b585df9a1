"""scripts/smoother-diagnosis.py's figures on made-up data (docs/smoother.md, "Why the smoothed
ATE is worse than the filter's"): a trajectory turned about its first pose gives back that
angle and nothing left once it is taken out; a measurement at the truth has chi^2 0 and one a
sigma off in bearing chi^2 1; landmarks seeing two objects and movers are named; the rotation
model's sigma shrinks with the first scan's bearings."""

import importlib.util
import math
import types

import pytest

from conftest import SOURCE_DIR

SPEC = importlib.util.spec_from_file_location(
    "smoother_diagnosis", SOURCE_DIR / "scripts" / "smoother-diagnosis.py")
diagnosis = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(diagnosis)


def truth_along_a_line(scans, posts):
    """{utime: (pose, objects)}: the robot drives along x at 0.125 m per scan, heading 0."""
    return {1000 * k: ((0.125 * k, 0.0, 0.0), posts) for k in range(scans)}


def test_a_turned_trajectory_gives_its_angle_and_nothing_else():
    posts = [(1, 5.0, 3.0, diagnosis.CLASS_STATIC, diagnosis.KIND_POST)]
    truth = truth_along_a_line(100, posts)
    # The map and every pose after the first turned by 10 mrad about the first pose, whose
    # heading (the anchor) is right.
    angle = 0.01
    c, s = math.cos(angle), math.sin(angle)
    poses = {u: (c * p[0] - s * p[1], s * p[0] + c * p[1], p[2] + (angle if u else 0.0))
             for u, (p, _) in truth.items()}
    landmarks = [(c * 5.0 - s * 3.0, s * 5.0 + c * 3.0)]
    figures = diagnosis.trajectory_figures(poses, landmarks, truth)
    assert figures["rotation_about_start_rad"] == pytest.approx(angle, abs=1e-9)
    assert figures["ate_without_rotation_m"] == pytest.approx(0.0, abs=1e-9)
    assert figures["ate_m"] > 0.05
    assert figures["landmark_rmse_without_rotation_m"] == pytest.approx(0.0, abs=1e-9)
    assert figures["landmark_rmse_m"] == pytest.approx(angle * math.hypot(5.0, 3.0), rel=1e-3)


def test_chi_square_whitens_by_the_measurement_covariance():
    covariance = (0.04, 0.0, 0.0, 0.0349 ** 2)
    assert diagnosis.chi_square((0.0, 0.0), covariance) == 0.0
    assert diagnosis.chi_square((0.0, 0.0349), covariance) == pytest.approx(1.0)
    assert diagnosis.chi_square((0.4, 0.0), covariance) == pytest.approx(4.0)


def observation(landmark, range_m, bearing_rad):
    return types.SimpleNamespace(landmark_id=landmark, range_m=range_m, bearing_rad=bearing_rad,
                                 covariance=(0.04, 0.0, 0.0, 0.0349 ** 2), tentative=False)


def scan(utime, observations, removed=()):
    return types.SimpleNamespace(utime=utime, sensor_forward_m=0.0, sensor_left_m=0.0,
                                 sensor_yaw_rad=0.0, observations=observations,
                                 removed_landmark_ids=list(removed))


def test_merged_landmarks_and_movers_are_named():
    static_a = (1, 10.0, 0.0, diagnosis.CLASS_STATIC, diagnosis.KIND_POST)
    static_b = (2, 10.0, 2.0, diagnosis.CLASS_STATIC, diagnosis.KIND_POST)
    mover = (3, 0.0, 10.0, 1, diagnosis.KIND_DISC)
    truth = {0: ((0.0, 0.0, 0.0), [static_a, static_b, mover])}
    b_bearing = math.atan2(2.0, 10.0)
    inputs = [
        # landmark 7 sees post a twice, then post b once; landmark 8 is the mover, removed
        scan(0, [observation(7, 10.0, 0.0), observation(8, 10.0, math.pi / 2)]),
        scan(0, [observation(7, 10.0, 0.0)]),
        scan(0, [observation(7, math.hypot(10.0, 2.0), b_bearing)], removed=[8]),
    ]
    records = diagnosis.observations_against_truth(inputs, truth)
    figures = diagnosis.observation_figures(inputs, records)
    assert figures["observations"] == 4
    assert figures["chi2_mean"] == pytest.approx(0.0, abs=1e-12)
    assert figures["sightings_on_other_objects"] == 1
    assert [m["landmark"] for m in figures["landmarks_on_several_objects"]] == [7]
    assert figures["landmarks_on_movers"] == [{"landmark": 8, "sightings": 1, "removed": True}]
    assert figures["mover_sightings_kept"] == 0


def test_the_first_scans_bearings_narrow_the_rotation():
    without = diagnosis.rotation_sigma_model(False, 1.0)
    with_first = diagnosis.rotation_sigma_model(True, 1.0)
    assert with_first < without
    # One scan's bearings alone know the heading to 2 deg / sqrt(19): more information only
    # narrows it.
    assert with_first < math.radians(2.0) / math.sqrt(19)
