"""TUM trajectory files (Sturm et al., IROS 2012; the format evo's `evo_ape tum` reads): one line
per pose, `timestamp x y z qx qy qz qw`, timestamp in seconds, position in metres, orientation
as a unit quaternion. The stack is planar: z = 0 and the quaternion turns by the heading about z.

| file | channel | frame |
|---|---|---|
| estimate.tum | POSE (pose_t) | the estimator's map frame (its start pose) |
| odometry.tum | ODOMETRY (odometry_t) | the base's odometry frame |
| truth.tum | GROUND_TRUTH (ground_truth_t robot pose) | the world frame |
| smoothed.tum | SMOOTHED_POSE (pose_t), when the log has it | the smoother's map frame |
| smoothed_final.tum | the last SMOOTHED_TRAJECTORY (trajectory_t): every keyframe as the smoother estimated it at the end | the smoother's map frame |

Each pose is written as it is, in its own frame: evo aligns them (`--align_origin` is
slammtt-eval's anchoring, `-a` its least-squares alignment). A trajectory without any pose is
not written.
"""

import os

from slammtt.export.files import number_text, seconds_text, write_text
from slammtt.geometry import yaw_quaternion

# file stem -> (channel key, function message -> (x_m, y_m, heading_rad))
TRAJECTORIES = {
    "estimate": ("pose", lambda m: (m.x_m, m.y_m, m.heading_rad)),
    "odometry": ("odometry", lambda m: (m.x_m, m.y_m, m.heading_rad)),
    "truth": ("ground_truth", lambda m: (m.robot_x_m, m.robot_y_m, m.robot_heading_rad)),
    "smoothed": ("smoothed_pose", lambda m: (m.x_m, m.y_m, m.heading_rad)),
}


def tum_line(utime, x_m, y_m, heading_rad):
    qx, qy, qz, qw = yaw_quaternion(heading_rad)
    return " ".join([seconds_text(utime)] + [number_text(float(v)) for v in
                                             (x_m, y_m, 0.0, qx, qy, qz, qw)])


def write_tum(data, directory):
    """Writes every trajectory the log has into `directory`; returns {stem: poses written}."""
    written = {}
    for stem, (key, pose_of) in TRAJECTORIES.items():
        messages = data[key]
        if not messages:
            continue
        lines = [tum_line(m.utime, *pose_of(m)) for m in messages]
        write_text(os.path.join(directory, stem + ".tum"), "\n".join(lines) + "\n")
        written[stem] = len(lines)
    final = data["smoothed_trajectory"]
    if final and final[-1].num_poses > 0:
        last = final[-1]
        lines = [tum_line(*pose) for pose in
                 zip(last.pose_utime, last.x_m, last.y_m, last.heading_rad)]
        write_text(os.path.join(directory, "smoothed_final.tum"), "\n".join(lines) + "\n")
        written["smoothed_final"] = len(lines)
    return written
