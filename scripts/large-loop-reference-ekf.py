#!/usr/bin/env python3
"""A reference EKF-SLAM on a large-loop world's truth (issue 14, docs/smoother.md "What keeps the
filter's heading sigma flat"): the true trajectory, posts and their visibility from the world
log, the estimator's models (odometry 1e-4 per metre, range 0.2 m, bearing 2 degrees, the laser
0.1 m ahead), its budget of static updates per scan (least recently updated first) and its local
window (40 m), and the association given. What covariance and errors an EKF has on the same
data when nothing is associated wrongly, to compare with the estimator's POSE.

Usage: large-loop-reference-ekf.py WORLD_LOG MODE BUDGET NOISE_SEED END_S [odo] [feat] [w=P]
  MODE     ekf (Jacobians at the estimates: the standard EKF) or ideal (at the truth: the
           consistent reference)
  BUDGET   static updates per scan (the estimator's 32; 0: all)
  odo      the world's ODOMETRY (else the true increments with the model's noise)
  feat     the world's FEATURES, each paired with the post nearest to it placed from the true
           pose (within 1 m), else features drawn from the visible posts with the model's noise
  w=P      each measurement of a mapped post paired instead with probability P with the nearest
           other landmark in the state (within 3 m): wrong associations at a rate P
Prints the heading and position errors and sigmas every 40 s. About 90 s for 330 s of run.
"""
import math
import os
import sys
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'python'))
from slammtt.lcmlog import LogReader
world = sys.argv[1]; mode = sys.argv[2]; B = int(sys.argv[3]); seed = int(sys.argv[4]) if len(sys.argv) > 4 else 1
rng = np.random.default_rng(seed)
real_odo = 'odo' in sys.argv[6:] ; real_feat = 'feat' in sys.argv[6:]
odo = []; feats = {}
traj = []; vis_sets = []; LM = None
for ev in LogReader(world):
    if ev.channel == 'GROUND_TRUTH':
        m = ev.message
        if LM is None:
            LM = {o.id: (o.x_m, o.y_m) for o in m.objects}
        traj.append((m.utime, m.robot_x_m, m.robot_y_m, m.robot_heading_rad))
        vis_sets.append([o.id for o in m.objects if o.visible])
    elif ev.channel == 'ODOMETRY':
        m = ev.message; odo.append((m.utime, m.x_m, m.y_m, m.heading_rad))
    elif ev.channel == 'FEATURES':
        m = ev.message; feats[m.utime] = [(f.range_m, f.bearing_rad) for f in m.features]
odo_t = np.array([o[0] for o in odo]); odo_p = np.array([o[1:] for o in odo])
def odo_at(t):
    i = int(np.searchsorted(odo_t, t)); i = min(max(i, 1), len(odo_t)-1)
    f = (t - odo_t[i-1])/(odo_t[i]-odo_t[i-1]); a, b = odo_p[i-1], odo_p[i]
    return np.array([a[0]+f*(b[0]-a[0]), a[1]+f*(b[1]-a[1]), a[2]+f*wrap(b[2]-a[2])])
ids_all = sorted(LM); LMa = np.array([LM[i] for i in ids_all]); idx_of = {i: k for k, i in enumerate(ids_all)}
def wrap(a): return (a+np.pi)%(2*np.pi)-np.pi
R = np.diag([0.2**2, math.radians(2)**2]); mount = 0.1
T = np.array([t[1:] for t in traj]); ut = np.array([t[0] for t in traj])
mu = T[0].copy(); P = np.zeros((3,3)); ids = []; last_up = {}
out = []
for k in range(1, len(T)):
    dt = (ut[k]-ut[k-1])/1e6
    a, b = T[k-1], T[k]
    rot = wrap(b[2]-a[2]); dx, dy = b[0]-a[0], b[1]-a[1]; d = math.hypot(dx, dy)
    qd = 1e-4*d + 1e-6*dt; qr = 1e-4*abs(rot) + 1e-4*d + 1e-6*dt
    d_o = d + rng.normal(0, math.sqrt(qd)); r_o = rot + rng.normal(0, math.sqrt(qr))
    if real_odo:
        oa, ob = odo_at(ut[k-1]), odo_at(ut[k])
        r_o = wrap(ob[2]-oa[2]); ddx, ddy = ob[0]-oa[0], ob[1]-oa[1]; d_o = math.hypot(ddx, ddy)
        if ddx*math.cos(ob[2]) + ddy*math.sin(ob[2]) < 0: d_o = -d_o
    lin = a if mode == 'ideal' else mu[:3]
    h = lin[2] + r_o
    F = np.eye(3); F[0,2] = -d_o*math.sin(h); F[1,2] = d_o*math.cos(h)
    G = np.array([[math.cos(h), -d_o*math.sin(h)], [math.sin(h), d_o*math.cos(h)], [0, 1]])
    hm = mu[2] + r_o
    mu[:3] = [mu[0]+d_o*math.cos(hm), mu[1]+d_o*math.sin(hm), wrap(hm)]
    P[:3,:] = F@P[:3,:]; P[:,:3] = P[:,:3]@F.T; P[:3,:3] += G@np.diag([qd,qr])@G.T
    xt = b
    vis = [idx_of[i] for i in vis_sets[k]]
    sens_t = xt[:2] + mount*np.array([math.cos(xt[2]), math.sin(xt[2])])
    zs = {}
    for j in vis:
        rel = LMa[j]-sens_t; r = math.hypot(*rel); be = wrap(math.atan2(rel[1], rel[0]) - xt[2])
        if r > 30 or abs(be) > math.pi/2: continue
        zs[j] = np.array([r + rng.normal(0, 0.2), be + rng.normal(0, math.radians(2))])
    if real_feat:
        zs = {}
        for (fr, fb) in feats.get(ut[k], []):
            pt = sens_t + fr*np.array([math.cos(xt[2]+fb), math.sin(xt[2]+fb)])
            dd = np.hypot(*(LMa - pt).T); j = int(np.argmin(dd))
            if dd[j] < 1.0 and j not in zs: zs[j] = np.array([fr, fb])
    known = [j for j in zs if j in ids]
    pw = float(next((a[2:] for a in sys.argv[6:] if a.startswith('w=')), 0))
    if pw > 0:
        pos0 = {j: 3+2*q for q, j in enumerate(ids)}
        z2 = {}
        for j in list(zs):
            if j in ids and rng.uniform() < pw:
                # pair this post's measurement with the nearest other landmark in the state
                others = [i for i in ids if i != j and i not in zs and i not in z2]
                if others:
                    dd = [np.hypot(*(mu[pos0[i]:pos0[i]+2] - mu[pos0[j]:pos0[j]+2])) for i in others]
                    i = others[int(np.argmin(dd))]
                    if min(dd) < 3.0: z2[i] = zs.pop(j)
        zs.update(z2)
        known = [j for j in zs if j in ids]
    if B and len(known) > B:
        known.sort(key=lambda j: (last_up.get(j, -1), j)); known = known[:B]
    for j in known: last_up[j] = k
    pos = {j: 3+2*q for q, j in enumerate(ids)}
    n = len(mu)
    for g in range(0, len(known), 32):
        grp = known[g:g+32]
        H = np.zeros((2*len(grp), n)); inn = np.zeros(2*len(grp))
        for q, j in enumerate(grp):
            p = pos[j]
            rl = xt if mode == 'ideal' else mu[:3]; ll = LMa[j] if mode == 'ideal' else mu[p:p+2]
            c, s = math.cos(rl[2]), math.sin(rl[2]); sp = rl[:2] + mount*np.array([c, s])
            ex, ey = ll - sp; qq = ex*ex+ey*ey; r = math.sqrt(qq)
            dsp_dth = mount*np.array([-s, c])
            Hl = np.array([[ex/r, ey/r], [-ey/qq, ex/qq]])
            Hr = np.zeros((2,3)); Hr[:, :2] = -Hl; Hr[:, 2] = -Hl@dsp_dth; Hr[1,2] -= 1
            H[2*q:2*q+2, :3] = Hr; H[2*q:2*q+2, p:p+2] = Hl
            cm, sm = math.cos(mu[2]), math.sin(mu[2]); spm = mu[:2] + mount*np.array([cm, sm])
            em = mu[p:p+2] - spm
            inn[2*q:2*q+2] = zs[j] - np.array([math.hypot(*em), wrap(math.atan2(em[1], em[0]) - mu[2])]); inn[2*q+1] = wrap(inn[2*q+1])
        S = H@P@H.T + np.kron(np.eye(len(grp)), R)
        K = np.linalg.solve(S, H@P).T
        mu = mu + K@inn; mu[2] = wrap(mu[2]); P = P - K@S@K.T; P = 0.5*(P+P.T)
    for j in zs:
        if j in ids: continue
        rr, bb = zs[j]
        rl = xt if mode == 'ideal' else mu[:3]
        c, s = math.cos(mu[2]), math.sin(mu[2]); spm = mu[:2] + mount*np.array([c, s])
        lm = spm + rr*np.array([math.cos(mu[2]+bb), math.sin(mu[2]+bb)])
        al = rl[2] + bb
        Gr = np.array([[1, 0, -rr*math.sin(al) - mount*math.sin(rl[2])], [0, 1, rr*math.cos(al) + mount*math.cos(rl[2])]])
        Gz = np.array([[math.cos(al), -rr*math.sin(al)], [math.sin(al), rr*math.cos(al)]])
        n = len(mu); Pn = np.zeros((n+2, n+2)); Pn[:n,:n] = P
        Pn[n:, :n] = Gr@P[:3, :]; Pn[:n, n:] = Pn[n:, :n].T; Pn[n:, n:] = Gr@P[:3,:3]@Gr.T + Gz@R@Gz.T
        P = Pn; mu = np.concatenate([mu, lm]); ids.append(j)
    keep = [q for q in range(len(ids)) if np.hypot(*(mu[3+2*q:5+2*q]-mu[:2])) <= 40]
    if len(keep) < len(ids):
        ix = [0,1,2] + [3+2*q+c for q in keep for c in (0,1)]
        P = P[np.ix_(ix, ix)]; mu = mu[ix]; ids = [ids[q] for q in keep]
    if k % 320 == 0:
        print("t %6.1f herr %6.2f hsig %5.2f deg  perr %5.2f psig %5.3f  n %d" % ((ut[k]-ut[0])/1e6, math.degrees(wrap(mu[2]-xt[2])), math.degrees(math.sqrt(P[2,2])), math.hypot(*(mu[:2]-xt[:2])), math.sqrt(P[0,0]+P[1,1]), len(ids)), flush=True)
    if (ut[k]-ut[0])/1e6 > float(sys.argv[5] if len(sys.argv) > 5 else 330): break
