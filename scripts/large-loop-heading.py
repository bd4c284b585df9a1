#!/usr/bin/env python3
"""The filter's heading and position against its own sigmas over a large-loop run (issue 14,
docs/smoother.md "What keeps the filter's heading sigma flat"): POSE (the filter's mean and
covariance) against GROUND_TRUTH, both in the frame of the first pose, every EVERY seconds.

Usage: large-loop-heading.py REPLAY_LOG [EVERY_S]   (a log of measure-large-loop.py --keep-logs)
Run with build/venv/bin/python (the log reader).
"""
import math
import os
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'python'))
from slammtt.lcmlog import LogReader
import numpy as np
path = sys.argv[1]
every = float(sys.argv[2]) if len(sys.argv) > 2 else 20.0
gt = {}; pose = {}; status = {}
for ev in LogReader(path):
    m = ev.message
    if ev.channel == 'GROUND_TRUTH': gt[m.utime] = (m.robot_x_m, m.robot_y_m, m.robot_heading_rad)
    elif ev.channel == 'POSE': pose[m.utime] = (m.x_m, m.y_m, m.heading_rad, np.array(m.covariance).reshape(3,3) if len(m.covariance)==9 else np.array(m.covariance))
    elif ev.channel == 'ESTIMATOR_STATUS': status[m.utime] = m
ts = sorted(t for t in pose if t in gt)
t0 = ts[0]; g0 = gt[t0]
c, s = math.cos(-g0[2]), math.sin(-g0[2])
def wrap(a): return (a + math.pi) % (2*math.pi) - math.pi
rows = []
for t in ts:
    gx, gy, gh = gt[t]
    dx, dy = gx - g0[0], gy - g0[1]
    tx, ty, th = c*dx - s*dy, s*dx + c*dy, wrap(gh - g0[2])
    x, y, h, P = pose[t]
    eh = wrap(h - th); ep = math.hypot(x - tx, y - ty)
    rows.append(((t-t0)/1e6, eh, math.sqrt(P[2,2]), ep, math.sqrt(max(P[0,0], P[1,1]) if True else 0), math.sqrt(P[0,0]+P[1,1])))
last = -1e9
for r in rows:
    if r[0] - last >= every:
        last = r[0]
        print(f"t {r[0]:6.1f}  heading err {math.degrees(r[1]):6.2f} sigma {math.degrees(r[2]):5.2f} deg  pos err {r[3]:5.2f} sigma {r[5]:5.3f} m")
late = [r for r in rows if r[0] >= 20.0]
print("from 20 s on: heading sigma %.2f-%.2f deg, mean heading NEES %.1f" % (
    math.degrees(min(r[2] for r in late)), math.degrees(max(r[2] for r in late)),
    float(np.mean([(r[1] / r[2])**2 for r in late]))))
