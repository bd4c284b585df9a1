"""The BreezySLAM text format -> ODOMETRY and LASER_SCAN (lines written here, in the format of
SOURCE.md; nothing of the LGPL files is copied)."""

import math

import numpy as np
import pytest

from slammtt.importer import breezyslam

from conftest import import_ok, read_log, run_import

TICKS_PER_TURN = 2000
WHEEL_CIRCUMFERENCE_M = 2 * math.pi * 0.077


def line(utime_us, left_ticks, right_ticks, ranges_mm):
    fields = [utime_us, 0, left_ticks, right_ticks] + [0] * 20 + list(ranges_mm) + [0]
    return " ".join(str(f) for f in fields) + "\n"


def ranges(*pairs, fill=1000):
    r = [fill] * breezyslam.BEAMS
    for index, value in pairs:
        r[index] = value
    return r


def test_fields_and_beams():
    utime, left, right, r = breezyslam.parse_line(line(5, 7, 9, ranges((0, 0), (681, 19))))
    assert (utime, left, right, len(r), r[0], r[1], r[681]) == (5, 7, 9, 682, 0, 1000, 19)
    angles = breezyslam.beam_angles_rad()
    assert angles[0] == pytest.approx(-math.radians(120))
    assert angles[-1] == pytest.approx(math.radians(120))
    assert angles[341] - angles[340] == pytest.approx(math.radians(240 / 681))


@pytest.mark.parametrize("text, why", [
    ("1 2 3\n", "fields"),
    (line(1, 0, 0, ranges()).replace(" 1000 ", " 1e3 ", 1), "not an integer"),
])
def test_malformed_lines_are_refused(text, why):
    with pytest.raises(breezyslam.LineRefused, match=why):
        breezyslam.parse_line(text)


def test_straight_line_and_turn_on_the_spot(tmp_path):
    path = tmp_path / "drive.dat"
    path.write_text(
        line(1_000_000, 100, 200, ranges()) +
        line(2_000_000, 100 + TICKS_PER_TURN, 200 + TICKS_PER_TURN, ranges()) +  # 1 turn each
        line(3_000_000, 100 + TICKS_PER_TURN - 500, 200 + TICKS_PER_TURN + 500, ranges()))
    refusals = breezyslam.Refusals()
    readings = list(breezyslam.read_readings(path, refusals))
    assert refusals.count == 0
    first, straight, turn = (r.odometry for r in readings)
    assert (first.x_m, first.y_m, first.heading_rad, first.linear_mps) == (0.0, 0.0, 0.0, 0.0)
    assert straight.x_m == pytest.approx(WHEEL_CIRCUMFERENCE_M)
    assert straight.y_m == pytest.approx(0.0, abs=1e-12)
    assert straight.linear_mps == pytest.approx(WHEEL_CIRCUMFERENCE_M)
    assert straight.left_wheel_mps == pytest.approx(WHEEL_CIRCUMFERENCE_M)
    # A quarter turn of each wheel in opposite directions: (dr - dl) / D.
    dphi = 2 * (WHEEL_CIRCUMFERENCE_M / 4) / 0.33
    assert turn.heading_rad == pytest.approx(dphi)
    assert turn.x_m == pytest.approx(WHEEL_CIRCUMFERENCE_M)
    assert turn.angular_radps == pytest.approx(dphi)
    assert turn.linear_mps == pytest.approx(0.0, abs=1e-12)


def test_import_writes_both_channels(tmp_path):
    path = tmp_path / "two.dat"
    path.write_text(line(1_000_000, 0, 0, ranges((0, 0), (1, 19), (2, 20), (3, 5600),
                                                 (4, 5601))) +
                    "this line is broken\n" +
                    line(1_100_000, 10, 10, ranges()))
    out = tmp_path / "two.lcm"
    err = import_ok(path, "-o", out)
    assert "skipped 1 malformed lines (first: line 2:" in err
    log = read_log(out)
    assert [m.utime for m in log["ODOMETRY"]] == [1_000_000, 1_100_000]
    scan = log["LASER_SCAN"][0]
    assert scan.num_beams == 682 and scan.sequence == 0
    assert scan.valid[:6] == [False, False, True, True, False, True]
    assert math.isinf(scan.range_m[0])            # 0 mm: no return
    assert scan.range_m[2] == pytest.approx(0.02)
    assert scan.range_min_m == pytest.approx(0.02) and scan.range_max_m == pytest.approx(5.6)
    assert scan.scan_duration_us == 66504
    yaml = (tmp_path / "two.lcm.mount.yaml").read_text()
    assert "  sensor_forward_m: 0.145\n  sensor_left_m: 0.0\n" in yaml
    np.testing.assert_allclose(scan.angle_rad, breezyslam.beam_angles_rad(), atol=1e-6)


def test_a_file_without_any_line_of_the_format_fails(tmp_path):
    path = tmp_path / "empty.dat"
    path.write_text("nothing here\n")
    status, _, err = run_import(path, "-o", tmp_path / "x.lcm")
    assert status == 1
    assert err.strip().endswith("no line of the breezyslam format (line 1: 2 fields, at "
                                "least 707 expected)")
    assert [l for l in err.splitlines() if "error" in l] == err.strip().splitlines()[-1:]
    assert not (tmp_path / "x.lcm").exists()


def test_a_line_out_of_time_order_is_refused(tmp_path):
    path = tmp_path / "order.dat"
    path.write_text(line(2_000_000, 0, 0, ranges()) + line(1_000_000, 5, 5, ranges()) +
                    line(2_000_000, 6, 6, ranges()) + line(2_100_000, 7, 7, ranges()))
    refusals = breezyslam.Refusals()
    readings = list(breezyslam.read_readings(path, refusals))
    assert [r.line_number for r in readings] == [1, 4]
    assert refusals.count == 2
    assert refusals.first == "line 2: timestamp 1000000 not after 2000000"
