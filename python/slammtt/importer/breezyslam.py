"""The text logs of BreezySLAM's "Mines" recordings (../shared/data/real/breezyslam_mines,
SOURCE.md) -> ODOMETRY and LASER_SCAN.

Format (as that repository's examples/mines.py reads it): one line per scan, whitespace
separated integers; field 0 = timestamp [us]; fields 2 and 3 = cumulative left / right wheel
encoder ticks; fields 24 .. 24 + BEAMS - 1 = ranges [mm]; the last token of a line is not a
range. Constants (SOURCE.md and mines.py; Hokuyo URG-04LX for the laser):
- wheels: 2000 ticks per turn, radius 77 mm, half axle 165 mm (D = 0.33 m);
- laser: 682 ranges over 240 deg, beam i at -120 + i * 240 / 681 deg, counter-clockwise
  (BreezySLAM's coreslam.c scan_update_xy); 0 = no return; URG-04LX range 20 mm to 5.6 m
  (values 1-19 are the scanner's error codes, below range_min: invalid); a sweep of 1024 steps
  takes 100 ms, so the 682 beams take 681 / 1024 * 100 ms = 66.5 ms (scan_duration_us);
- mount: the laser 145 mm ahead of the axle centre (mines.py: MinesLaser offset_mm = 145),
  yaw 0.
A line with too few fields, a field that is not an integer, or a timestamp not after the
previous one is refused (one line with the line number) and counted; the rest is imported.
"""

import dataclasses
import math

import numpy as np

from slammtt.importer.laser import Scan, classify_beams
from slammtt.importer.mount import Mount
from slammtt.importer.odometry import TickIntegrator, WheelGeometry

BEAMS = 682
FIRST_RANGE_FIELD = 24
FIELD_OF_VIEW_DEG = 240.0
RANGE_MIN_M = 0.02
RANGE_MAX_M = 5.6
SCAN_DURATION_US = int(round(681 / 1024 * 100_000))
WHEELS = WheelGeometry(wheel_radius_m=0.077, axle_length_m=2 * 0.165, ticks_per_turn=2000)
MOUNT = Mount(forward_m=0.145, left_m=0.0, yaw_rad=0.0,
              source="BreezySLAM mines.py: the laser 145 mm ahead of the axle centre")


class LineRefused(ValueError):
    pass


@dataclasses.dataclass
class Reading:
    """One line: the odometry and the scan taken at its timestamp."""
    line_number: int
    odometry: object
    scan: Scan


def beam_angles_rad():
    step = math.radians(FIELD_OF_VIEW_DEG) / (BEAMS - 1)
    return -math.radians(FIELD_OF_VIEW_DEG) / 2 + np.arange(BEAMS, dtype=np.float64) * step


def parse_line(text):
    """(utime, left_ticks, right_ticks, ranges_mm) of one line; LineRefused if malformed."""
    fields = text.split()
    needed = FIRST_RANGE_FIELD + BEAMS + 1
    if len(fields) < needed:
        raise LineRefused(f"{len(fields)} fields, at least {needed} expected")
    try:
        utime = int(fields[0])
        left, right = int(fields[2]), int(fields[3])
        ranges = [int(f) for f in fields[FIRST_RANGE_FIELD:FIRST_RANGE_FIELD + BEAMS]]
    except ValueError as error:
        raise LineRefused(f"not an integer ({error})") from None
    return utime, left, right, ranges


class Refusals:
    def __init__(self):
        self.count = 0
        self.first = ""

    def add(self, line_number, why):
        if self.count == 0:
            self.first = f"line {line_number}: {why}"
        self.count += 1


def read_readings(path, refusals):
    """Every well-formed line of the file as a Reading, in file order."""
    integrator = TickIntegrator(WHEELS)
    angles = beam_angles_rad().astype(np.float32)
    last_utime = None
    with open(path, "rt", encoding="ascii", errors="replace") as text:
        for line_number, line in enumerate(text, start=1):
            if not line.strip():
                continue
            try:
                utime, left, right, ranges_mm = parse_line(line)
                if last_utime is not None and utime <= last_utime:
                    raise LineRefused(f"timestamp {utime} not after {last_utime}")
            except LineRefused as error:
                refusals.add(line_number, str(error))
                continue
            last_utime = utime
            ranges = np.asarray(ranges_mm, dtype=np.float64) / 1000.0
            no_return = ranges == 0.0
            # 0 is the scanner's "no return": REP 117 writes it +inf.
            ranges[no_return] = math.inf
            valid, counts = classify_beams(ranges, RANGE_MIN_M, RANGE_MAX_M)
            scan = Scan(utime=utime, scan_duration_us=SCAN_DURATION_US,
                        range_min_m=RANGE_MIN_M, range_max_m=RANGE_MAX_M, angle_rad=angles,
                        range_m=ranges.astype(np.float32),
                        intensity=np.zeros(BEAMS, dtype=np.float32), valid=valid,
                        counts=counts)
            yield Reading(line_number, integrator.update(utime, left, right), scan)

