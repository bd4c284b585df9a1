"""CSV tables of a log (docs/export.md, "CSV"): one row per pose, track, landmark or feature and
message, a header row, units in the column names, numbers that read back to the same double.
Frames: poses and truth in their own frames (as in the log), tracks and landmarks in the
estimator's map frame, features in the sensor frame (x forward, y left)."""

import math
import os

from slammtt.export.files import write_csv

TRACK_CLASSES = {0: "static", 1: "moving", 2: "undecided"}
TRACK_KINDS = {0: "other", 1: "person"}
TRUTH_CLASSES = {0: "static", 1: "moving"}
TRUTH_KINDS = {0: "unknown", 1: "wall", 2: "furniture", 3: "post", 4: "disc", 5: "person",
               6: "leg"}


def _pose_rows(data):
    for m in data["pose"]:
        c = list(m.covariance)
        yield ("estimate", m.utime, m.x_m, m.y_m, m.heading_rad, c[0], c[4], c[8], c[1], "", "")
    for m in data["smoothed_pose"]:
        c = list(m.covariance)
        yield ("smoothed", m.utime, m.x_m, m.y_m, m.heading_rad, c[0], c[4], c[8], c[1], "", "")
    for m in data["odometry"]:
        yield ("odometry", m.utime, m.x_m, m.y_m, m.heading_rad, "", "", "", "",
               m.linear_velocity_mps, m.angular_velocity_radps)
    for m in data["ground_truth"]:
        yield ("truth", m.utime, m.robot_x_m, m.robot_y_m, m.robot_heading_rad, "", "", "", "",
               m.robot_linear_mps, m.robot_angular_radps)


def _track_rows(data):
    for m in data["tracks"]:
        for t in m.tracks:
            c = list(t.covariance)
            yield (m.utime, t.id, TRACK_CLASSES.get(t.object_class, str(t.object_class)),
                   t.confirmed, t.x_m, t.y_m, t.vx_mps, t.vy_mps, c[0], c[1], c[5], c[10],
                   c[15], t.hits, t.first_seen_utime, t.last_seen_utime,
                   TRACK_KINDS.get(t.kind, str(t.kind)), t.measured, t.coasting_s, t.reported)


def _landmark_rows(data, key):
    for m in data[key]:
        for l in m.landmarks:
            c = list(l.covariance)
            yield (m.utime, l.id, l.x_m, l.y_m, c[0], c[1], c[3])


def _map_rows(data):
    return _landmark_rows(data, "map")


def _smoothed_map_rows(data):
    return _landmark_rows(data, "smoothed_map")


def _map_line_rows(data):
    for m in data["map"]:
        for l in m.lines:
            c = list(l.covariance)
            yield (m.utime, l.id, l.rho_m, l.alpha_rad, c[0], c[1], c[3], l.from_x_m,
                   l.from_y_m, l.to_x_m, l.to_y_m, l.hits)


def _point_rows(data):
    for m in data["features"]:
        for i, f in enumerate(m.features):
            yield (m.utime, m.sequence, i, f.range_m, f.bearing_rad,
                   f.range_m * math.cos(f.bearing_rad), f.range_m * math.sin(f.bearing_rad),
                   f.width_m, f.num_points, f.range_var_m2, f.bearing_var_rad2,
                   f.range_bearing_cov_m_rad, f.leg_likeness)


def _line_rows(data):
    for m in data["features"]:
        for i, f in enumerate(m.lines):
            yield (m.utime, m.sequence, i, f.rho_m, f.alpha_rad, f.rho_var_m2, f.alpha_var_rad2,
                   f.rho_alpha_cov_m_rad, f.first_x_m, f.first_y_m, f.last_x_m, f.last_y_m,
                   f.num_points, f.rms_residual_m)


def _person_rows(data):
    for m in data["features"]:
        for i, p in enumerate(m.people):
            yield (m.utime, m.sequence, i, p.range_m, p.bearing_rad,
                   p.range_m * math.cos(p.bearing_rad), p.range_m * math.sin(p.bearing_rad),
                   p.range_var_m2, p.bearing_var_rad2, p.range_bearing_cov_m_rad, p.num_legs,
                   p.leg_index[0], p.leg_index[1], p.confidence)


def _truth_rows(data):
    for m in data["ground_truth"]:
        for o in m.objects:
            yield (m.utime, o.id, TRUTH_KINDS.get(o.kind, str(o.kind)),
                   TRUTH_CLASSES.get(o.object_class, str(o.object_class)), o.parent_id, o.x_m,
                   o.y_m, o.vx_mps, o.vy_mps, o.radius_m, o.beams_on_object, o.visible)


TABLES = {
    "poses.csv": (("source", "utime_us", "x_m", "y_m", "heading_rad", "var_x_m2", "var_y_m2",
                   "var_heading_rad2", "cov_xy_m2", "linear_velocity_mps",
                   "angular_velocity_radps"), _pose_rows),
    "tracks.csv": (("utime_us", "id", "class", "confirmed", "x_m", "y_m", "vx_mps", "vy_mps",
                    "var_x_m2", "cov_xy_m2", "var_y_m2", "var_vx_m2ps2", "var_vy_m2ps2", "hits",
                    "first_seen_utime_us", "last_seen_utime_us", "kind", "measured",
                    "coasting_s", "reported"), _track_rows),
    "map.csv": (("utime_us", "id", "x_m", "y_m", "var_x_m2", "cov_xy_m2", "var_y_m2"),
                _map_rows),
    "smoothed_map.csv": (("utime_us", "id", "x_m", "y_m", "var_x_m2", "cov_xy_m2", "var_y_m2"),
                         _smoothed_map_rows),
    "map_lines.csv": (("utime_us", "id", "rho_m", "alpha_rad", "var_rho_m2", "cov_rho_alpha_m_rad",
                       "var_alpha_rad2", "from_x_m", "from_y_m", "to_x_m", "to_y_m", "hits"),
                      _map_line_rows),
    "features.csv": (("utime_us", "sequence", "index", "range_m", "bearing_rad", "x_m", "y_m",
                      "width_m", "num_points", "range_var_m2", "bearing_var_rad2",
                      "range_bearing_cov_m_rad", "leg_likeness"), _point_rows),
    "line_features.csv": (("utime_us", "sequence", "index", "rho_m", "alpha_rad", "rho_var_m2",
                           "alpha_var_rad2", "rho_alpha_cov_m_rad", "first_x_m", "first_y_m",
                           "last_x_m", "last_y_m", "num_points", "rms_residual_m"), _line_rows),
    "person_features.csv": (("utime_us", "sequence", "index", "range_m", "bearing_rad", "x_m",
                             "y_m", "range_var_m2", "bearing_var_rad2",
                             "range_bearing_cov_m_rad", "num_legs", "leg_index_0",
                             "leg_index_1", "confidence"), _person_rows),
    "truth_objects.csv": (("utime_us", "id", "kind", "class", "parent_id", "x_m", "y_m",
                           "vx_mps", "vy_mps", "radius_m", "beams_on_object", "visible"),
                          _truth_rows),
}


def write_tables(data, directory):
    """Every table into `directory` (header only when the log has none of its rows); returns
    {file name: rows}."""
    counts = {}
    for name, (header, rows_of) in TABLES.items():
        rows = list(rows_of(data))
        write_csv(os.path.join(directory, name), header, rows)
        counts[name] = len(rows)
    return counts
