"""The laser geometry of an imported recording as LASER_GEOMETRY messages (laser_geometry_t).

The estimator takes the mount, the field of view and the maximum range from the log when its
configuration does not give them (docs/estimator.md, "Laser geometry"), so the import writes
what it found: the mount it chose (the bag's transform, the --mount-* options or BreezySLAM's),
the field of view the first scan's beams span, in the frame the beams are written in, and the
first scan's range limits. One message at the first scan and then one at the first scan of
every further second of scan time: the same input gives the same messages.
"""

import dataclasses
import math

import numpy as np

from slammtt.importer.geometry import wrap_angle

PERIOD_US = 1_000_000


@dataclasses.dataclass
class View:
    """Bearings from start_rad counter-clockwise to end_rad (the laser_geometry_t fields)."""
    start_rad: float = -math.pi
    end_rad: float = math.pi


def view_of_beams(angles_rad):
    """The view a scan's beams span: the circle without its widest gap between neighbouring
    beams, centred where its middle is (so that both ends lie within a turn of 0). A scan whose
    widest gap is at most twice its median spacing covers the full circle (-pi, pi)."""
    a = np.sort(np.array([wrap_angle(float(x)) for x in angles_rad], dtype=np.float64))
    if a.size < 2:
        return View()
    gaps = np.diff(np.append(a, a[0] + 2.0 * math.pi))
    widest = int(np.argmax(gaps))
    if gaps[widest] <= 2.0 * float(np.median(gaps)):
        return View()
    start = float(a[(widest + 1) % a.size])
    width = 2.0 * math.pi - float(gaps[widest])
    middle = wrap_angle(start + 0.5 * width)
    return View(start_rad=middle - 0.5 * width, end_rad=middle + 0.5 * width)


def geometry_messages(scans, mount, rotated_to_base, source):
    """(utime, laser_geometry_t) at the first scan and at the first scan of every further
    second; [] without scans. With --rotate-to-base the beams are in the robot's orientation,
    so the mount's yaw is 0 and the view is that of the rotated beams."""
    from slammtt_msgs import laser_geometry_t
    if not scans:
        return []
    first = scans[0]
    view = view_of_beams(first.angle_rad)

    def message(utime):
        m = laser_geometry_t()
        m.utime = int(utime)
        m.mount_forward_m = float(mount.forward_m)
        m.mount_left_m = float(mount.left_m)
        m.mount_yaw_rad = 0.0 if rotated_to_base else float(mount.yaw_rad)
        m.view_start_rad = view.start_rad
        m.view_end_rad = view.end_rad
        m.range_min_m = float(first.range_min_m)
        # REP 117 lets range_max be +inf (no stated limit): the estimator then keeps its own.
        m.range_max_m = float(first.range_max_m)
        m.source = source
        return m

    out = []
    next_utime = None
    for scan in scans:
        if next_utime is None or scan.utime >= next_utime:
            out.append((int(scan.utime), message(scan.utime)))
            next_utime = int(scan.utime) + PERIOD_US
    return out
