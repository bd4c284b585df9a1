#!/usr/bin/env python3
"""What the movers that are no person are: each one named by the world object it sits on.

    build/venv/bin/python scripts/non-person-movers.py OUTDIR [--label ml_ransac-no-odometry]

Reads the runs that scripts/measure-estimator.py left in OUTDIR (SCENARIO-SEED-LABEL.out.lcm and
its .people.json, whose detail.people_tracking.false_mover_ids are slammtt-eval's movers that are
no person). For every such track, every scan in which it was reported MOVING is placed in the
world frame through the robot: its map position relative to the estimated POSE of that scan,
put at the true robot pose of the same utime (so that an error of the robot's estimate does not
move it onto another object). The nearest true object to its mean place is named: a compact
object of GROUND_TRUTH (post, furniture leg, person, leg) by its centre's distance less its
radius, a segment (wall, furniture side) by the distance to the segment. Prints one row per
mover and a count per kind; every figure also in OUTDIR/non-person-movers.json.
"""
import argparse
import collections
import glob
import json
import math
import os
import re

from slammtt.lcmlog import LogReader

KINDS = {1: "wall", 2: "furniture", 3: "post", 4: "disc", 5: "person", 6: "leg"}


def segment_distance(p, a, b):
    ax, ay = a
    bx, by = b
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / length2))
    return math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy)


def to_world(track_xy, pose, truth):
    """The map point `track_xy` seen from the estimated `pose`, placed at the true robot pose."""
    ex, ey, eh = pose
    rx, ry = track_xy[0] - ex, track_xy[1] - ey
    c, s = math.cos(-eh), math.sin(-eh)
    lx, ly = c * rx - s * ry, s * rx + c * ry
    tx, ty, th = truth
    c, s = math.cos(th), math.sin(th)
    return (tx + c * lx - s * ly, ty + s * lx + c * ly)


def analyse(lcm_path, ids):
    poses, truths, samples = {}, {}, collections.defaultdict(list)
    statics = {}
    segments = {}
    people = collections.defaultdict(list)  # utime -> [(x, y)] of people and legs
    for m in LogReader(lcm_path):
        msg = m.message
        if m.channel == "POSE":
            poses[msg.utime] = (msg.x_m, msg.y_m, msg.heading_rad)
        elif m.channel == "GROUND_TRUTH":
            truths[msg.utime] = (msg.robot_x_m, msg.robot_y_m, msg.robot_heading_rad)
            for o in msg.objects:
                if o.object_class == 0:
                    statics[o.id] = (o.kind, o.x_m, o.y_m, o.radius_m)
                elif o.kind in (5, 6):
                    people[msg.utime].append((o.x_m, o.y_m))
            for s in msg.segments:
                segments[s.id, s.x0_m, s.y0_m] = (s.kind, (s.x0_m, s.y0_m), (s.x1_m, s.y1_m))
        elif m.channel == "TRACKS":
            for t in msg.tracks:
                if t.id in ids and t.reported and t.object_class == 1:
                    samples[t.id].append((msg.utime, (t.x_m, t.y_m), math.hypot(t.vx_mps,
                                                                                 t.vy_mps)))
    rows = []
    for track_id in sorted(ids):
        placed = [(u, to_world(xy, poses[u], truths[u]), v) for u, xy, v in samples[track_id]
                  if u in poses and u in truths]
        if not placed:
            continue
        mx = sum(p[0] for _, p, _ in placed) / len(placed)
        my = sum(p[1] for _, p, _ in placed) / len(placed)
        spread = max(math.hypot(p[0] - mx, p[1] - my) for _, p, _ in placed)
        best = (math.inf, "none", -1)
        for oid, (kind, x, y, r) in statics.items():
            d = max(0.0, math.hypot(mx - x, my - y) - r)
            best = min(best, (d, KINDS.get(kind, str(kind)), oid))
        for (sid, _, _), (kind, a, b) in segments.items():
            best = min(best, (segment_distance((mx, my), a, b), KINDS.get(kind, str(kind)), sid))
        near_person = min((math.hypot(mx - x, my - y) for u, _, _ in placed
                           for x, y in people.get(u, [])), default=math.inf)
        rows.append({"track_id": track_id, "scans_moving": len(placed),
                     "first_s": (placed[0][0] - min(truths)) * 1e-6,
                     "x_m": round(mx, 3), "y_m": round(my, 3), "spread_m": round(spread, 3),
                     "mean_speed_mps": round(sum(v for _, _, v in placed) / len(placed), 3),
                     "nearest_kind": best[1], "nearest_id": best[2],
                     "nearest_m": round(best[0], 3),
                     "nearest_person_m": round(near_person, 3)})
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir")
    parser.add_argument("--label", default="ml_ransac-no-odometry",
                        help="the run label of the file names (ml_ransac, ml_ransac-no-odometry)")
    args = parser.parse_args()
    pattern = re.compile(r"(.+)-(\d+)-" + re.escape(args.label) + r"\.people\.json$")
    results = []
    for path in sorted(glob.glob(os.path.join(args.outdir, f"*-{args.label}.people.json"))):
        match = pattern.match(os.path.basename(path))
        if not match:
            continue
        with open(path) as f:
            ids = set(json.load(f)["detail"]["people_tracking"].get("false_mover_ids", []))
        lcm_path = path[:-len(".people.json")] + ".out.lcm"
        for row in analyse(lcm_path, ids) if ids else []:
            row.update(scenario=match.group(1), seed=int(match.group(2)))
            results.append(row)
    keys = ["scenario", "seed", "track_id", "first_s", "scans_moving", "x_m", "y_m", "spread_m",
            "mean_speed_mps", "nearest_kind", "nearest_id", "nearest_m", "nearest_person_m"]
    print("| " + " | ".join(keys) + " |")
    print("|" + "---|" * len(keys))
    for r in sorted(results, key=lambda r: (r["scenario"], r["seed"], r["track_id"])):
        cells = [f"{r[k]:.1f}" if k == "first_s" else str(r[k]) for k in keys]
        print("| " + " | ".join(cells) + " |")
    counts = collections.Counter((r["scenario"], r["nearest_kind"]) for r in results)
    print("\nnearest kind per scenario: " +
          ", ".join(f"{s} {k} {n}" for (s, k), n in sorted(counts.items())))
    with open(os.path.join(args.outdir, "non-person-movers.json"), "w") as f:
        json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
