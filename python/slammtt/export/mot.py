"""MOTChallenge files of a log's people tracking (docs/export.md, "MOTChallenge"): the truth in
the layout of MOT16's gt.txt, the tracker output in the layout of MOTChallenge result files, in
the folder layout TrackEval's MotChallenge2DBox reads (with SKIP_SPLIT_FOL):

  DIR/gt/SEQ/gt/gt.txt                 frame,id,bb_left,bb_top,w,h,flag,class,visibility
  DIR/gt/SEQ/seqinfo.ini               seqLength, frameRate
  DIR/trackers/slammtt/data/SEQ.txt    frame,id,bb_left,bb_top,w,h,conf,-1,-1,-1
  DIR/frames.csv                       frame -> utime_us

The stack tracks points on the floor, not boxes in an image. Every object and track is written
as the axis-aligned square of side `box_m` centred on its position, in metres of the plane
(bb_left = x - box_m / 2, bb_top = y - box_m / 2, y not mirrored): distances between the
(bb_left, bb_top) corners are exactly the distances between the points, so an evaluation by
Euclidean distance on those columns (py-motmetrics' 'euc' with distfields X, Y) sees the
stack's geometry; the point is bb_left + box_m / 2, bb_top + box_m / 2. The track files' last
three columns (MOTChallenge's 3D x, y, z) are -1, as in MOTChallenge's 2D results: TrackEval
reads the eighth column of a result row as its class and refuses any above 1. An
evaluation by box overlap (IoU) sees squares whose overlap falls with distance, which no box
side makes equal to a distance threshold in every direction.

Which truth and which tracks, as slammtt-eval scores them (docs/evaluation.md, "Tracking"):
frames are the GROUND_TRUTH scans from the first to the last TRACKS message; an object is a
mover (class MOVING; a person's legs are folded into the person, whose beams are those of its
better-seen leg); flag 1 (scored) when it is visible (LASER_SCAN logs: min_beams beams; feature
logs: the world's flag) and not standing (true speed >= min_moving_speed_mps), flag 0 (ignored
by MOTChallenge evaluations) when it is standing (visibility 1) or not visible (visibility 0);
class 1 (pedestrian). Tracks: reported (confirmed and measured within the estimator's
tracks_report_measured_within_s; a coasting track is not written), labelled moving, anchored into the truth frame by
slammtt-eval's anchoring. Unlike slammtt-eval, no evaluation of these files excuses a track
near an invisible mover or on a standing one unless it applies MOTChallenge's ignore flag.
"""

import math
import os

from slammtt.export.files import number_text, write_csv, write_text

KIND_PERSON = 5
KIND_LEG = 6
CLASS_MOVING = 1
TRACK_CLASS_MOVING = 1
MOT_CLASS_PEDESTRIAN = 1


class TruthRules:
    """The visibility and standing rules of slammtt-eval (docs/evaluation.md)."""

    def __init__(self, min_beams=3, min_moving_speed_mps=0.2, scan_log=False):
        self.min_beams = min_beams
        self.min_moving_speed_mps = min_moving_speed_mps
        self.scan_log = scan_log

    def movers(self, truth):
        """[(id, x_m, y_m, visible, standing)] of the movers of one ground_truth_t."""
        leg_beams = {}
        for o in truth.objects:
            if o.kind == KIND_LEG:
                leg_beams[o.parent_id] = max(leg_beams.get(o.parent_id, 0), o.beams_on_object)
        out = []
        for o in truth.objects:
            if o.kind == KIND_LEG or o.object_class != CLASS_MOVING:
                continue
            beams = leg_beams.get(o.id, 0) if o.kind == KIND_PERSON else o.beams_on_object
            visible = beams >= self.min_beams if self.scan_log else bool(o.visible)
            standing = math.hypot(o.vx_mps, o.vy_mps) < self.min_moving_speed_mps
            out.append((o.id, o.x_m, o.y_m, visible, standing))
        return out


def frames_of(data):
    """[(frame number from 1, utime)]: the GROUND_TRUTH scans from the first to the last TRACKS
    message (every TRACKS message when the log has no ground truth)."""
    tracks = data["tracks"]
    truth = data["ground_truth"]
    if not truth:
        return [(k + 1, m.utime) for k, m in enumerate(tracks)]
    if tracks:
        first, last = tracks[0].utime, tracks[-1].utime
        truth = [m for m in truth if first <= m.utime <= last]
    return [(k + 1, m.utime) for k, m in enumerate(truth)]


def _box(x_m, y_m, box_m):
    return x_m - box_m / 2.0, y_m - box_m / 2.0, box_m, box_m


def write_mot(data, directory, sequence, rules, box_m=1.0):
    """Writes the files above; returns a dict of counts and the frame of the tracks."""
    frames = frames_of(data)
    frame_of_utime = {utime: frame for frame, utime in frames}
    anchor = data.truth_anchor()
    tracks_frame = "world (anchored)" if anchor else "map"
    transform = anchor[1] if anchor else None
    counts = {"frames": len(frames), "truth_rows": 0, "truth_scored": 0, "track_rows": 0,
              "tracks_frame": tracks_frame, "tracks_messages_outside_frames": 0}

    truth_lines = []
    for m in data["ground_truth"]:
        frame = frame_of_utime.get(m.utime)
        if frame is None:
            continue
        for object_id, x_m, y_m, visible, standing in rules.movers(m):
            flag = 1 if visible and not standing else 0
            truth_lines.append(",".join(number_text(v) for v in (
                frame, object_id, *_box(x_m, y_m, box_m), flag, MOT_CLASS_PEDESTRIAN,
                1.0 if visible else 0.0)))
            counts["truth_rows"] += 1
            counts["truth_scored"] += flag

    track_lines = []
    for m in data["tracks"]:
        frame = frame_of_utime.get(m.utime)
        if frame is None:
            counts["tracks_messages_outside_frames"] += 1
            continue
        for t in m.tracks:
            if not t.reported or t.object_class != TRACK_CLASS_MOVING:
                continue
            x_m, y_m = transform.apply(t.x_m, t.y_m) if transform else (t.x_m, t.y_m)
            track_lines.append(",".join(number_text(v) for v in (
                frame, t.id, *_box(x_m, y_m, box_m), 1.0, -1, -1, -1)))
            counts["track_rows"] += 1

    if data["ground_truth"]:
        write_text(os.path.join(directory, "gt", sequence, "gt", "gt.txt"),
                   "".join(line + "\n" for line in truth_lines))
        write_text(os.path.join(directory, "gt", sequence, "seqinfo.ini"),
                   _seqinfo(sequence, frames))
    write_text(os.path.join(directory, "trackers", "slammtt", "data", sequence + ".txt"),
               "".join(line + "\n" for line in track_lines))
    write_csv(os.path.join(directory, "frames.csv"), ("frame", "utime_us"), frames)
    return counts


def _seqinfo(sequence, frames):
    periods = sorted(b[1] - a[1] for a, b in zip(frames, frames[1:]) if b[1] > a[1])
    rate = round(1e6 / periods[len(periods) // 2]) if periods else 1
    return ("[Sequence]\n"
            f"name={sequence}\n"
            "imDir=img1\n"
            f"frameRate={rate}\n"
            f"seqLength={len(frames)}\n"
            "imWidth=1\n"
            "imHeight=1\n"
            "imExt=.jpg\n")
