#!/usr/bin/env python3
"""Error decomposition of the people score (issue 13): why each person-scan was missed, why each
output track was a false positive, and where the identity switches are.

    build/venv/bin/python scripts/people-errors.py OUTDIR [--runs office-11,corridor-14]
        [--label ml_ransac] [--match-m 0.75] [--min-beams 3] [--json FILE]

Reads the runs that scripts/measure-estimator.py left in OUTDIR (SCENARIO-SEED-LABEL.out.lcm)
and re-does slammtt-eval's people score (tools/eval/evaluation.cc, tools/metrics/clear_mot.cc:
truth = visible people, standing ones counted; output = reported tracks labelled MOVING or of
kind PERSON; CLEAR-MOT matching with carried-over correspondences; unmatched tracks within the
threshold of an invisible person excused), then names a cause for every error:

misses (a visible person with no matched output track), by the nearest track of any state:
  tentative       a tentative track within the threshold (late confirmation)
  unreported      a confirmed track within the threshold not reported (coasting, report rule)
  not-a-person    a reported track within the threshold, UNDECIDED or STATIC of kind other
  taken           an output track within the threshold, matched to another person
  far             the nearest track is 0.75-2 m away (a track behind its person)
  none            no track within 2 m
false positives (an output track neither matched nor excused), by its state and surroundings:
  KIND/CLASS/measured|coasting, and what it sits on: 'person' (a person within 2 m: a second
  track on a person or one left behind), 'furniture', 'post', 'wall' (within 0.5 m of a static
  object or segment), else 'free'.
Every figure per run is also written to --json.
"""
import argparse
import collections
import glob
import json
import math
import os
import re

import numpy as np
from scipy.optimize import linear_sum_assignment

from slammtt.lcmlog import LogReader

PERSON, LEG, WALL, FURNITURE, POST = 5, 6, 1, 2, 3
CLASS_NAMES = {0: "STATIC", 1: "MOVING", 2: "UNDECIDED"}


def seg_dist(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    l2 = dx * dx + dy * dy
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2))
    return math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy)


def anchor_of(truth_pose, est_pose):
    """T with T * estimate = truth (pose composition)."""
    tx, ty, th = truth_pose
    ex, ey, eh = est_pose
    dh = th - eh
    c, s = math.cos(dh), math.sin(dh)
    return (tx - (c * ex - s * ey), ty - (s * ex + c * ey), dh)


def apply(anchor, p):
    ax, ay, ah = anchor
    c, s = math.cos(ah), math.sin(ah)
    return (ax + c * p[0] - s * p[1], ay + s * p[0] + c * p[1])


def assign(cost, threshold):
    if cost.size == 0:
        return []
    big = 1e6
    c = np.where(cost <= threshold, cost, big)
    rows, cols = linear_sum_assignment(c)
    return [(r, k) for r, k in zip(rows, cols) if c[r, k] < big]


def analyse(path, match_m, min_beams):
    truths, tracks, poses = {}, {}, {}
    for m in LogReader(path):
        if m.channel == "GROUND_TRUTH":
            truths[m.message.utime] = m.message
        elif m.channel == "TRACKS":
            tracks[m.message.utime] = m.message
        elif m.channel == "POSE":
            poses[m.message.utime] = m.message
    scan_log = True
    anchor = None
    for u in sorted(truths):
        if u in poses:
            g, p = truths[u], poses[u]
            anchor = anchor_of((g.robot_x_m, g.robot_y_m, g.robot_heading_rad),
                               (p.x_m, p.y_m, p.heading_rad))
            break
    if anchor is None or not tracks:
        return None
    begin, end = min(tracks), max(tracks)
    last_hyp = {}          # truth id -> last matched hypothesis
    last_obj = {}          # hyp id -> last truth id
    misses = collections.Counter()
    fps = collections.Counter()
    fp_tracks = collections.defaultdict(collections.Counter)
    miss_people = collections.defaultdict(collections.Counter)
    switches = []
    n_truth = n_match = 0
    for u in sorted(truths):
        if u < begin or u > end:
            continue
        g = truths[u]
        tm = tracks.get(u)
        people, dont_care = [], []
        statics, persons_all = [], []
        # A person is visible when one of its legs has min_beams beams (eval_log.cc).
        leg_beams = collections.Counter()
        for o in g.objects:
            if o.kind == LEG:
                leg_beams[o.parent_id] = max(leg_beams[o.parent_id], o.beams_on_object)
        for o in g.objects:
            if o.kind == PERSON:
                persons_all.append((o.x_m, o.y_m))
                if leg_beams[o.id] >= min_beams:
                    people.append((o.id, (o.x_m, o.y_m), math.hypot(o.vx_mps, o.vy_mps)))
                else:
                    dont_care.append((o.x_m, o.y_m))
            elif o.object_class == 0 and o.kind in (FURNITURE, POST):
                statics.append((o.kind, (o.x_m, o.y_m), o.radius_m))
        all_tracks, hyps = [], []
        if tm is not None:
            for t in tm.tracks:
                p = apply(anchor, (t.x_m, t.y_m))
                rec = (t, p)
                all_tracks.append(rec)
                if t.reported and (t.object_class == 1 or t.kind == 1):
                    hyps.append(rec)
        hid = {t.id: j for j, (t, p) in enumerate(hyps)}
        t2h = [-1] * len(people)
        taken = [False] * len(hyps)

        def d(i, j):
            return math.dist(people[i][1], hyps[j][1])
        for i, (pid, pp, _) in enumerate(people):
            h = last_hyp.get(pid)
            if h is None or h not in hid or last_obj.get(h) != pid:
                continue
            if d(i, hid[h]) > match_m:
                continue
            t2h[i] = hid[h]
            taken[hid[h]] = True
        ft = [i for i in range(len(people)) if t2h[i] < 0]
        fh = [j for j in range(len(hyps)) if not taken[j]]
        cost = np.array([[d(i, j) for j in fh] for i in ft]).reshape(len(ft), len(fh))
        for a, b in assign(cost, match_m):
            i, j = ft[a], fh[b]
            t2h[i] = j
            taken[j] = True
            pid = people[i][0]
            if pid in last_hyp and last_hyp[pid] != hyps[j][0].id:
                old = last_hyp[pid]
                switches.append({"utime": u, "person": pid, "from": old, "to": hyps[j][0].id})
        for i, (pid, pp, speed) in enumerate(people):
            n_truth += 1
            j = t2h[i]
            if j >= 0:
                n_match += 1
                last_hyp[pid] = hyps[j][0].id
                last_obj[hyps[j][0].id] = pid
                continue
            # cause of the miss
            near = sorted(((math.dist(pp, p), t) for t, p in all_tracks), key=lambda x: x[0])
            cause = "none"
            for dist, t in near:
                if dist > match_m:
                    if dist <= 2.0 and cause == "none":
                        cause = "far"
                    break
                if not t.confirmed:
                    c = "tentative"
                elif not t.reported:
                    c = "unreported"
                elif not (t.object_class == 1 or t.kind == 1):
                    c = "not-a-person:" + CLASS_NAMES[t.object_class]
                else:
                    c = "taken"
                cause = c
                break
            cause += "/standing" if speed < 0.2 else ""
            misses[cause] += 1
            miss_people[pid][cause] += 1
        # false positives
        unmatched = [j for j in range(len(hyps)) if not taken[j]]
        for j in unmatched:
            t, p = hyps[j]
            if any(math.dist(p, q) <= match_m for q in dont_care):
                continue
            kind = "person" if t.kind == 1 else "other"
            state = "measured" if t.measured else "coasting"
            near_person = min((math.dist(p, q) for q in persons_all), default=99)
            where = "free"
            if near_person <= 2.0:
                where = "person"
            else:
                ds = min((math.dist(p, q) - r for k, q, r in statics), default=99)
                dw = min((seg_dist(p, (s.x0_m, s.y0_m), (s.x1_m, s.y1_m)) for s in g.segments),
                         default=99) if hasattr(g, "segments") and g.segments and hasattr(
                             g.segments[0], "x0_m") else 99
                if ds <= 0.5:
                    where = "furniture/post"
                elif dw <= 0.5:
                    where = "wall"
            key = f"{kind}/{CLASS_NAMES[t.object_class]}/{state}/{where}"
            fps[key] += 1
            fp_tracks[t.id][key] += 1
    fp_total = sum(fps.values())
    miss_total = sum(misses.values())
    mota = 1 - (miss_total + fp_total + len(switches)) / max(n_truth, 1)
    return {"truth": n_truth, "matches": n_match, "misses": miss_total, "false": fp_total,
            "switches": len(switches), "mota": mota, "miss_causes": dict(misses),
            "false_causes": dict(fps),
            "false_tracks": {str(k): dict(v) for k, v in
                             sorted(fp_tracks.items(), key=lambda kv: -sum(kv[1].values()))},
            "miss_people": {str(k): dict(v) for k, v in miss_people.items()},
            "switch_list": switches}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--runs", default="")
    ap.add_argument("--label", default="ml_ransac")
    ap.add_argument("--match-m", type=float, default=0.75)
    ap.add_argument("--min-beams", type=int, default=3)
    ap.add_argument("--json", default="")
    ap.add_argument("--tracks", type=int, default=8, help="false tracks listed per run")
    args = ap.parse_args()
    paths = sorted(glob.glob(os.path.join(args.outdir, f"*-{args.label}.out.lcm")))
    wanted = set(args.runs.split(",")) if args.runs else None
    results = {}
    for path in paths:
        name = os.path.basename(path)[:-len(f"-{args.label}.out.lcm")]
        if wanted and name not in wanted:
            continue
        r = analyse(path, args.match_m, args.min_beams)
        if r is None:
            continue
        results[name] = r
        print(f"== {name}: people MOTA {r['mota']:.3f}: {r['truth']} person-scans, "
              f"{r['misses']} misses, {r['false']} false, {r['switches']} switches")
        print("  misses: " + ", ".join(f"{k} {v}" for k, v in
                                       sorted(r["miss_causes"].items(), key=lambda kv: -kv[1])))
        print("  false:  " + ", ".join(f"{k} {v}" for k, v in
                                       sorted(r["false_causes"].items(), key=lambda kv: -kv[1])))
        for tid, causes in list(r["false_tracks"].items())[:args.tracks]:
            print(f"    track {tid}: " + ", ".join(f"{k} {v}" for k, v in causes.items()))
    total_m, total_f = collections.Counter(), collections.Counter()
    for r in results.values():
        total_m.update(r["miss_causes"])
        total_f.update(r["false_causes"])
    print("== all runs: misses " + ", ".join(f"{k} {v}" for k, v in total_m.most_common()))
    print("== all runs: false " + ", ".join(f"{k} {v}" for k, v in total_f.most_common()))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
