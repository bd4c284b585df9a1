"""LaserScan -> laser_scan_t: REP 117 beams, angles, duration, refused geometry."""

import math
import types

import numpy as np
import pytest

from slammtt.importer import laser


def laser_scan(ranges, angle_min=-1.0, increment=0.5, range_min=0.1, range_max=5.0,
               time_increment=1e-3, intensities=()):
    return types.SimpleNamespace(
        ranges=np.asarray(ranges, dtype=np.float32), angle_min=angle_min,
        angle_increment=increment, range_min=range_min, range_max=range_max,
        time_increment=time_increment, intensities=np.asarray(intensities, dtype=np.float32))


def test_rep117_beam_classes():
    ranges = [1.0, math.inf, -math.inf, math.nan, 0.05, 6.0, 0.1, 5.0, 0.0]
    scan = laser.scan_from_laser_scan(laser_scan(ranges, increment=0.1), 7)
    assert scan.valid.tolist() == [True, False, False, False, False, False, True, True, False]
    c = scan.counts
    assert (c.valid, c.no_return, c.too_close, c.invalid, c.below_min, c.above_max) == \
        (3, 1, 1, 1, 2, 1)
    assert c.total() == len(ranges)
    # The values stay as REP 117 made them.
    assert math.isinf(scan.range_m[1]) and scan.range_m[1] > 0
    assert math.isinf(scan.range_m[2]) and scan.range_m[2] < 0
    assert math.isnan(scan.range_m[3])


def test_angles_from_angle_min_and_increment_wrapped():
    scan = laser.scan_from_laser_scan(
        laser_scan([1.0] * 5, angle_min=2.5, increment=0.5), 0)
    expected = [2.5, 3.0, 3.5 - 2 * math.pi, 4.0 - 2 * math.pi, 4.5 - 2 * math.pi]
    np.testing.assert_allclose(scan.angle_rad, np.float32(expected), atol=1e-6)
    assert scan.angle_rad.dtype == np.float32


def test_pi_wraps_to_pi_not_minus_pi():
    scan = laser.scan_from_laser_scan(laser_scan([1.0, 1.0], angle_min=-math.pi,
                                                 increment=math.pi), 0)
    assert scan.angle_rad.tolist() == [np.float32(math.pi), 0.0]


def test_duration_first_to_last_beam():
    scan = laser.scan_from_laser_scan(laser_scan([1.0] * 769, time_increment=-1e-4), 0)
    assert scan.scan_duration_us == 76800
    nan_time = laser.scan_from_laser_scan(laser_scan([1.0] * 3, time_increment=math.nan), 0)
    assert nan_time.scan_duration_us == 0


def test_intensities_copied_or_zero():
    same = laser.scan_from_laser_scan(laser_scan([1.0, 2.0], intensities=[5, 6]), 0)
    assert same.intensity.tolist() == [5.0, 6.0] and not same.intensities_dropped
    none = laser.scan_from_laser_scan(laser_scan([1.0, 2.0]), 0)
    assert none.intensity.tolist() == [0.0, 0.0] and not none.intensities_dropped
    other = laser.scan_from_laser_scan(laser_scan([1.0, 2.0], intensities=[5]), 0)
    assert other.intensity.tolist() == [0.0, 0.0] and other.intensities_dropped


@pytest.mark.parametrize("fields, why", [
    (dict(angle_min=math.nan), "not finite"),
    (dict(increment=math.inf), "not finite"),
    (dict(increment=0.0), "angle_increment 0"),
    (dict(range_min=math.nan), "range limits"),
    (dict(range_min=3.0, range_max=2.0), "range limits"),
    (dict(range_min=-1.0), "range limits"),
])
def test_unusable_geometry_is_refused(fields, why):
    with pytest.raises(laser.ScanRefused, match=why):
        laser.scan_from_laser_scan(laser_scan([1.0, 2.0], **fields), 0)


def test_hostile_beam_count_is_refused():
    with pytest.raises(laser.ScanRefused, match="beams"):
        laser.scan_from_laser_scan(laser_scan(np.ones(laser.MAX_BEAMS + 1)), 0)


def test_infinite_range_max_is_no_limit():
    scan = laser.scan_from_laser_scan(laser_scan([100.0], range_max=math.inf), 0)
    assert scan.valid.tolist() == [True]


def test_message_fields():
    scan = laser.scan_from_laser_scan(laser_scan([1.0, math.inf], intensities=[3, 4]), 123)
    m = laser.to_message(scan, 9)
    assert (m.utime, m.sequence, m.num_beams, m.scan_duration_us) == (123, 9, 2, 1000)
    assert m.valid == [True, False]
    assert m.intensity == [3.0, 4.0]
    assert m.range_min_m == pytest.approx(0.1) and m.range_max_m == 5.0
