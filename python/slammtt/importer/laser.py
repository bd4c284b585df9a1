"""sensor_msgs/LaserScan -> laser_scan_t, with the beams read as REP 117 says.

REP 117 (https://www.ros.org/reps/rep-0117.html, "Informational Distance Measurements"):
  +inf          no return: nothing within range_max          -> valid false, counted no_return
  -inf          an object closer than the sensor can measure -> valid false, counted too_close
  NaN           an erroneous measurement                     -> valid false, counted invalid
  finite < range_min                                         -> valid false, counted below_min
  finite > range_max                                         -> valid false, counted above_max
  otherwise                                                  -> valid true
The range value itself is kept as the bag has it (laser_scan_t: "meaningless where valid is
false"), so +inf/-inf/NaN stay what REP 117 made them. Beam i points at angle_min +
i * angle_increment (computed in double, wrapped to (-pi, pi] as every angle of the stack), in
the laser's frame, x forward, y left. scan_duration_us = |time_increment| * (n - 1) (first to
last beam), 0 when time_increment is 0 or not finite. Intensities are copied when there is one
per beam, else 0 (an empty intensities array means the device gives none; another length is
counted in Scan.intensities_dropped).

A scan whose geometry is unusable (no finite angle_min / angle_increment, an increment of 0
with several beams, more than MAX_BEAMS beams, range limits NaN, range_min infinite, or not
0 <= range_min <= range_max; range_max may be +inf) is refused: ScanRefused with one line,
counted by the caller.
"""

import dataclasses
import math

import numpy as np

from slammtt.importer.geometry import wrap_angles

# Far above any 2D laser (a 0.1-degree 360-degree scanner has 3600 beams); a larger scan is a
# corrupt message, not a sensor.
MAX_BEAMS = 100_000


class ScanRefused(ValueError):
    """A LaserScan that cannot become a laser_scan_t (one line why)."""


@dataclasses.dataclass
class BeamCounts:
    """How the beams of the imported scans were classified (REP 117)."""
    valid: int = 0
    no_return: int = 0
    too_close: int = 0
    invalid: int = 0
    below_min: int = 0
    above_max: int = 0

    def add(self, other):
        for field in dataclasses.fields(self):
            setattr(self, field.name, getattr(self, field.name) + getattr(other, field.name))

    def total(self):
        return sum(dataclasses.astuple(self))

    def line(self):
        return ", ".join(f"{getattr(self, f.name)} {f.name.replace('_', ' ')}"
                         for f in dataclasses.fields(self))


@dataclasses.dataclass
class Scan:
    """One scan in the laser frame, ready for laser_scan_t (float32 arrays, as the message)."""
    utime: int
    scan_duration_us: int
    range_min_m: float
    range_max_m: float
    angle_rad: np.ndarray
    range_m: np.ndarray
    intensity: np.ndarray
    valid: np.ndarray
    counts: BeamCounts
    intensities_dropped: bool = False


def classify_beams(ranges, range_min_m, range_max_m):
    """(valid mask, BeamCounts) of float ranges under REP 117 (table above)."""
    r = np.asarray(ranges, dtype=np.float64)
    nan = np.isnan(r)
    pos_inf = np.isposinf(r)
    neg_inf = np.isneginf(r)
    finite = np.isfinite(r)
    below = finite & (r < range_min_m)
    above = finite & (r > range_max_m)
    valid = finite & ~below & ~above
    counts = BeamCounts(valid=int(valid.sum()), no_return=int(pos_inf.sum()),
                        too_close=int(neg_inf.sum()), invalid=int(nan.sum()),
                        below_min=int(below.sum()), above_max=int(above.sum()))
    return valid, counts


def scan_from_laser_scan(msg, utime):
    """A Scan from a deserialised sensor_msgs/LaserScan (ROS 1 or ROS 2) stamped `utime`."""
    ranges = np.asarray(msg.ranges, dtype=np.float32)
    n = int(ranges.size)
    if n > MAX_BEAMS:
        raise ScanRefused(f"{n} beams (more than {MAX_BEAMS})")
    angle_min = float(msg.angle_min)
    increment = float(msg.angle_increment)
    if not (math.isfinite(angle_min) and math.isfinite(increment)):
        raise ScanRefused(f"angle_min {angle_min} / angle_increment {increment} not finite")
    if n > 1 and increment == 0.0:
        raise ScanRefused(f"angle_increment 0 with {n} beams")
    range_min = float(msg.range_min)
    range_max = float(msg.range_max)
    if not (math.isfinite(range_min) and not math.isnan(range_max)
            and 0.0 <= range_min <= range_max):
        raise ScanRefused(f"range limits [{range_min}, {range_max}] not 0 <= min <= max")
    angles = wrap_angles(angle_min + np.arange(n, dtype=np.float64) * increment)
    valid, counts = classify_beams(ranges, range_min, range_max)
    intensities = np.asarray(msg.intensities, dtype=np.float32)
    intensities_dropped = intensities.size not in (0, n)
    if intensities.size != n:
        intensities = np.zeros(n, dtype=np.float32)
    time_increment = float(msg.time_increment)
    duration_us = 0
    if math.isfinite(time_increment) and n > 1:
        duration_us = int(round(abs(time_increment) * (n - 1) * 1e6))
    return Scan(utime=utime, scan_duration_us=duration_us, range_min_m=range_min,
                range_max_m=range_max, angle_rad=angles.astype(np.float32), range_m=ranges,
                intensity=intensities, valid=valid, counts=counts,
                intensities_dropped=intensities_dropped)


def to_message(scan, sequence):
    """laser_scan_t of a Scan, with its per-channel sequence number."""
    from slammtt_msgs import laser_scan_t
    message = laser_scan_t()
    message.utime = int(scan.utime)
    message.sequence = int(sequence)
    message.scan_duration_us = int(scan.scan_duration_us)
    message.range_min_m = float(scan.range_min_m)
    message.range_max_m = float(scan.range_max_m)
    message.num_beams = int(scan.range_m.size)
    message.angle_rad = scan.angle_rad.astype(np.float32).tolist()
    message.range_m = scan.range_m.astype(np.float32).tolist()
    message.intensity = scan.intensity.astype(np.float32).tolist()
    message.valid = [bool(v) for v in scan.valid]
    return message
