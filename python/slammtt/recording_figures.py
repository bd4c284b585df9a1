"""Figures of a replayed real recording, which has no ground truth (issue 13, "Real recordings"):
what the estimator reports about people, and how sharp the walls are when every scan is placed
by a trajectory. scripts/measure-real.py runs the programs and prints them; the definitions are
here, once, and in docs/targets.md.

People (TRACKS, lcmtypes/track_t.lcm; FEATURES, lcmtypes/features_t.lcm):
- a *reported person* is a track with `reported` (confirmed and measured within
  tracks_report_measured_within_s) and `kind == KIND_PERSON`;
- *person identities* are the distinct ids that were a reported person in at least one scan;
  per minute: that count over the span from the first to the last TRACKS message;
- *leg pairs* of a scan are the person features of its FEATURES message made of two legs
  (`num_legs == 2`): the people perception paired from legs. A recording without labels has no
  truer count; this is agreement with perception, not correctness. *Person features* are all of
  them (pairs and single legs).

Sharpness of the map (scans placed by a trajectory at their utime; the motion during one sweep
is ignored for every trajectory alike):
- *wall points* are the beams of a scan that lie on one of the line features perception found
  in that scan (within WALL_TOLERANCE_M of the line, inside its observed extent): the same beams
  whichever trajectory places them;
- *wall spread*: the plane is cut into square cells (CELL_M); in every cell holding at least
  MIN_CELL_POINTS wall points, the total-least-squares line of its points; the figure is the
  RMS, over the points of those cells, of their distance to their cell's line. A wall seen twice
  at an offset or an angle (a blurred map) widens its cells' spread; corners widen it too,
  equally for every trajectory, so the figure compares trajectories on one recording, not
  recordings with each other;
- *occupied cells*: the number of OCCUPANCY_CELL_M cells holding a wall point (a sharper map
  covers fewer);
- *distance to map lines*: each wall point's distance to the nearest line landmark of a MAP
  message (the segment of its observed extent); the RMS over the points within LINE_NEAR_M of
  one, and their share. The lines are the estimator's own, so this figure favours the
  estimator's trajectory over another one.
"""

import math

import numpy as np

CELL_M = 1.0
MIN_CELL_POINTS = 20
OCCUPANCY_CELL_M = 0.05
LINE_NEAR_M = 0.5
WALL_TOLERANCE_M = 0.05
KIND_PERSON = 1


def read_channels(path):
    """{channel: [message, ...]} of an LCM log, every event decoded (an undecodable event is a
    ValueError naming it: figures of a partly read log would be wrong)."""
    from slammtt.lcmlog import LogReader
    reader = LogReader(path, strict=True)
    channels = {}
    for m in reader:
        channels.setdefault(m.channel, []).append(m.message)
    if reader.undecodable:
        raise ValueError(f"{path}: {reader.first_undecodable}")
    return channels


# ---- people ----

def reported_people(tracks):
    """Reported person tracks of one TRACKS message."""
    return [t for t in tracks.tracks if t.reported and t.kind == KIND_PERSON]


def span_minutes(messages):
    """Minutes from the first to the last message's utime (0 for fewer than two)."""
    if len(messages) < 2:
        return 0.0
    return (messages[-1].utime - messages[0].utime) * 1e-6 / 60.0


def person_identities_per_minute(tracks_messages):
    """(distinct ids ever a reported person, that count per minute of the TRACKS span)."""
    ids = {t.id for m in tracks_messages for t in reported_people(m)}
    minutes = span_minutes(tracks_messages)
    return len(ids), (len(ids) / minutes if minutes > 0 else float("nan"))


def leg_pairs(features):
    """People perception paired from two legs in one FEATURES message."""
    return sum(1 for p in features.people if p.num_legs == 2)


def count_agreement(tracks_messages, features_messages):
    """Per scan (TRACKS and FEATURES matched by utime; scans with only one are left out): the
    reported people against the leg pairs and against all person features.
    {"scans", "match_pairs", "match_person_features", "mean_reported", "mean_pairs",
    "mean_person_features"} with the shares in [0, 1]."""
    features_by_utime = {f.utime: f for f in features_messages}
    reported, pairs, person_features = [], [], []
    for m in tracks_messages:
        f = features_by_utime.get(m.utime)
        if f is None:
            continue
        reported.append(len(reported_people(m)))
        pairs.append(leg_pairs(f))
        person_features.append(f.num_people)
    n = len(reported)
    if n == 0:
        raise ValueError("no scan has both TRACKS and FEATURES")
    return {
        "scans": n,
        "match_pairs": sum(r == p for r, p in zip(reported, pairs)) / n,
        "match_person_features": sum(r == p for r, p in zip(reported, person_features)) / n,
        "mean_reported": sum(reported) / n,
        "mean_pairs": sum(pairs) / n,
        "mean_person_features": sum(person_features) / n,
    }


# ---- placing scans ----

def trajectory_at(poses, utimes):
    """(N, 3) array of (x_m, y_m, heading_rad) of messages with utime, x_m, y_m, heading_rad,
    linearly interpolated at `utimes` (heading unwrapped first; held at the ends)."""
    t = np.array([p.utime for p in poses], dtype=np.float64)
    if len(t) == 0 or np.any(np.diff(t) <= 0):
        raise ValueError("a trajectory needs poses in increasing utime")
    heading = np.unwrap([p.heading_rad for p in poses])
    at = np.asarray(utimes, dtype=np.float64)
    return np.stack([np.interp(at, t, [p.x_m for p in poses]),
                     np.interp(at, t, [p.y_m for p in poses]),
                     np.interp(at, t, heading)], axis=1)


def wall_beams(scan, features, tolerance_m=WALL_TOLERANCE_M):
    """Boolean mask of the valid beams of `scan` within tolerance_m of one of the line features
    of `features` (the FEATURES message of that scan, sensor frame) and inside its extent."""
    valid = np.array(scan.valid, dtype=bool)
    r = np.where(valid, np.array(scan.range_m, dtype=np.float64), 0.0)
    a = np.array(scan.angle_rad, dtype=np.float64)
    x, y = r * np.cos(a), r * np.sin(a)
    on_wall = np.zeros(len(r), dtype=bool)
    for line in features.lines:
        off_m = np.abs(x * math.cos(line.alpha_rad) + y * math.sin(line.alpha_rad) - line.rho_m)
        ex, ey = line.last_x_m - line.first_x_m, line.last_y_m - line.first_y_m
        length_m = math.hypot(ex, ey)
        if not length_m > 0:
            continue
        along_m = ((x - line.first_x_m) * ex + (y - line.first_y_m) * ey) / length_m
        on_wall |= (off_m <= tolerance_m) & (along_m >= -tolerance_m) & \
            (along_m <= length_m + tolerance_m)
    return on_wall & valid


def scan_points(scans, trajectory, mount, masks=None):
    """(M, 2) map-frame points of the valid beams of `scans` (laser_scan_t; with `masks`, the
    beams each mask selects), scan i placed by trajectory[i] (x_m, y_m, heading_rad of the
    robot) and the laser by `mount` (forward_m, left_m, yaw_rad) on the robot (paper eq. 11
    with the sensor yaw)."""
    forward_m, left_m, yaw_rad = mount
    chunks = []
    for i, (scan, (x, y, heading)) in enumerate(zip(scans, trajectory)):
        use = np.array(scan.valid, dtype=bool) if masks is None else masks[i]
        r = np.array(scan.range_m, dtype=np.float64)[use]
        a = np.array(scan.angle_rad, dtype=np.float64)[use] + yaw_rad
        rx, ry = forward_m + r * np.cos(a), left_m + r * np.sin(a)
        c, s = math.cos(heading), math.sin(heading)
        chunks.append(np.stack([x + c * rx - s * ry, y + s * rx + c * ry], axis=1))
    return np.concatenate(chunks) if chunks else np.zeros((0, 2))


# ---- sharpness ----

def cell_line_spread(points, cell_m=CELL_M, min_points=MIN_CELL_POINTS):
    """(RMS distance [m] of the points of cells with >= min_points points to their cell's
    total-least-squares line, number of those points). NaN and 0 when no cell qualifies."""
    cells = np.floor(points / cell_m).astype(np.int64)
    _, cell_of_point, counts = np.unique(cells, axis=0, return_inverse=True, return_counts=True)
    cell_of_point = cell_of_point.reshape(-1)

    def per_cell(values):
        return np.bincount(cell_of_point, weights=values, minlength=len(counts))

    # Centred in each cell before the second moments, so that large coordinates lose nothing.
    mean_x = per_cell(points[:, 0]) / counts
    mean_y = per_cell(points[:, 1]) / counts
    dx = points[:, 0] - mean_x[cell_of_point]
    dy = points[:, 1] - mean_y[cell_of_point]
    sxx, sxy, syy = per_cell(dx * dx), per_cell(dx * dy), per_cell(dy * dy)
    # Smallest eigenvalue of the cell's scatter matrix: the sum of squared distances to the
    # total-least-squares line.
    half_trace = (sxx + syy) / 2.0
    smallest = half_trace - np.sqrt(((sxx - syy) / 2.0) ** 2 + sxy ** 2)
    used = counts >= min_points
    n = int(counts[used].sum())
    if n == 0:
        return float("nan"), 0
    return math.sqrt(max(float(smallest[used].sum()), 0.0) / n), n


def occupied_cells(points, cell_m=OCCUPANCY_CELL_M):
    """Number of cell_m square cells holding at least one point."""
    if len(points) == 0:
        return 0
    return len(np.unique(np.floor(points / cell_m).astype(np.int64), axis=0))


def line_segments(map_message):
    """(K, 4) array of the observed extents (from_x, from_y, to_x, to_y) of a MAP's lines."""
    return np.array([[l.from_x_m, l.from_y_m, l.to_x_m, l.to_y_m] for l in map_message.lines],
                    dtype=np.float64).reshape(-1, 4)


def distance_to_segments(points, segments, chunk=20000):
    """Distance [m] of each point to the nearest segment (inf without segments)."""
    out = np.full(len(points), np.inf)
    if len(segments) == 0:
        return out
    a, b = segments[:, 0:2], segments[:, 2:4]
    ab = b - a
    length2 = np.maximum((ab ** 2).sum(axis=1), 1e-18)
    for start in range(0, len(points), chunk):
        p = points[start:start + chunk, None, :]                      # (n, 1, 2)
        u = np.clip(((p - a) * ab).sum(axis=2) / length2, 0.0, 1.0)   # (n, K)
        nearest = a + u[:, :, None] * ab
        out[start:start + chunk] = np.sqrt(((p - nearest) ** 2).sum(axis=2)).min(axis=1)
    return out


def map_line_distance(points, segments, near_m=LINE_NEAR_M):
    """(RMS distance [m] of the points within near_m of a segment, their share of all points)."""
    d = distance_to_segments(points, segments)
    near = d <= near_m
    if not near.any():
        return float("nan"), 0.0
    return math.sqrt(float(np.mean(d[near] ** 2))), float(near.mean())


def sharpness(points, segments):
    """Every sharpness figure of one placement of the wall points (module docstring)."""
    spread_m, spread_points = cell_line_spread(points)
    line_rms_m, near_share = map_line_distance(points, segments)
    return {"wall_points": int(len(points)), "wall_spread_m": spread_m,
            "wall_spread_points": spread_points, "occupied_cells": occupied_cells(points),
            "map_line_rms_m": line_rms_m, "map_line_share": near_share}
