#!/usr/bin/env python3
"""How many of the filter's static sightings are of another post than their landmark's (issue
14, docs/smoother.md "What keeps the filter's heading sigma flat"): each SMOOTHER_INPUT
observation is labelled with the visible post of least NIS from the true pose; a landmark's own
post is the label most of its first five sightings have. Per time bin, per range (before the
return at 330 s), per landmark (sightings off its most sighted post) and per post (posts mapped
as two or more landmarks). The labels themselves are wrong for about 2 % of features (drawn with
the model's noise from the visible posts of seed 16's world and labelled the same way).

Usage: large-loop-off-post.py REPLAY_LOG WORLD_LOG [BIN_S] [labels]
  labels: also the share of wrong labels (features drawn with the model's noise from the posts
          visible at every 8th scan, labelled the same way)
"""
import math
import os
import sys
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'python'))
from slammtt.lcmlog import LogReader
from collections import defaultdict, Counter
log = sys.argv[1]; world = sys.argv[2]; binw = float(sys.argv[3]) if len(sys.argv) > 3 else 10
gt = {}; LM = None; visible = {}
for ev in LogReader(world):
    if ev.channel == 'GROUND_TRUTH':
        m = ev.message
        if LM is None:
            ids = [o.id for o in m.objects]; LM = np.array([(o.x_m, o.y_m) for o in m.objects])
        gt[m.utime] = (m.robot_x_m, m.robot_y_m, m.robot_heading_rad)
        visible[m.utime] = np.array([o.visible for o in m.objects])
t0 = min(gt)
sight = []  # (t, landmark_id, post)
for ev in LogReader(log):
    if ev.channel != 'SMOOTHER_INPUT': continue
    m = ev.message
    if m.utime not in gt: continue
    x, y, h = gt[m.utime]; sx, sy = x + 0.1*math.cos(h), y + 0.1*math.sin(h)
    vis = np.where(visible[m.utime])[0]
    if len(vis) == 0: continue
    rel = LM[vis] - [sx, sy]; rr = np.hypot(rel[:,0], rel[:,1]); bb = np.arctan2(rel[:,1], rel[:,0]) - h
    for o in m.observations:
        if o.tentative: continue
        db = (o.bearing_rad - bb + np.pi) % (2*np.pi) - np.pi
        nis = (o.range_m - rr)**2/0.04 + db**2/math.radians(2)**2
        sight.append(((m.utime - t0)/1e6, o.landmark_id, int(vis[np.argmin(nis)]), o.range_m, sorted(nis)[1] if len(nis)>1 else 99))
first = defaultdict(list)
for t, lid, post, *_ in sight:
    if len(first[lid]) < 5: first[lid].append(post)
own = {lid: Counter(p).most_common(1)[0][0] for lid, p in first.items()}
bins = defaultdict(lambda: [0, 0]); rb = defaultdict(lambda: [0, 0])
for t, lid, post, r, _ in sight:
    b = int(t // binw); bins[b][0] += 1; bins[b][1] += post != own[lid]
    if t < 330: rb[int(r // 5)][0] += 1; rb[int(r // 5)][1] += post != own[lid]
for b in sorted(rb): print(f"range {5*b:2d}-{5*b+5:2d} m (t < 330 s): sightings {rb[b][0]:6d} off own post {rb[b][1]:5d} ({100*rb[b][1]/rb[b][0]:4.1f} %)")
for b in sorted(bins):
    n, w = bins[b]; print(f"t {b*binw:5.0f}-{(b+1)*binw:5.0f}  sightings {n:5d}  off own post {w:4d} ({100*w/n:4.1f} %)")
per = defaultdict(Counter)
for t, lid, post, r, _ in sight:
    if t < 330: per[lid][post] += 1
tot = sum(sum(c.values()) for c in per.values())
off_modal = sum(sum(c.values()) - c.most_common(1)[0][1] for c in per.values())
split = [lid for lid, c in per.items() if len(c) > 1 and c.most_common(2)[1][1] >= 5]
print(f"t<330: {len(per)} landmarks, sightings {tot}, off the landmark's modal post {off_modal} ({100*off_modal/tot:.1f} %), landmarks with >=5 sightings of a second post: {len(split)}")
# two posts of one landmark: how far apart
d = [np.hypot(*(LM[per[l].most_common(2)[0][0]] - LM[per[l].most_common(2)[1][0]])) for l in split]
print("  their two posts apart (m): median %.2f  p90 %.2f" % (np.median(d), np.percentile(d, 90)) if d else "")
# posts seen through two or more landmarks
bypost = defaultdict(Counter)
for lid, c in per.items():
    for p, n in c.items(): bypost[p][lid] += n
dup = [p for p, c in bypost.items() if len(c) > 1 and c.most_common(2)[1][1] >= 5]
print(f"  posts sighted as >=2 landmarks (>=5 sightings each): {len(dup)} of {len(bypost)}")

if "labels" in sys.argv[4:]:
    rng = np.random.default_rng(0)
    n = wrong = 0
    for k, t in enumerate(sorted(gt)):
        if k % 8:
            continue
        x, y, h = gt[t]
        sx, sy = x + 0.1*math.cos(h), y + 0.1*math.sin(h)
        vis = np.where(visible[t])[0]
        rel = LM[vis] - [sx, sy]; rr = np.hypot(rel[:, 0], rel[:, 1]); bb = np.arctan2(rel[:, 1], rel[:, 0]) - h
        for i in range(len(vis)):
            zr = rr[i] + rng.normal(0, 0.2); zb = bb[i] + rng.normal(0, math.radians(2))
            db = (zb - bb + np.pi) % (2*np.pi) - np.pi
            n += 1; wrong += int(np.argmin((zr - rr)**2/0.04 + db**2/math.radians(2)**2)) != i
    print(f"labels wrong: {wrong} of {n} features drawn from the visible posts ({100*wrong/n:.1f} %)")
