#!/usr/bin/python3
"""Independent numpy re-implementation of evo's alignments and RPE pair selections, to
cross-check `rgbdvo eval --align ... --align-first ... --delta-unit frames|m` (Grupp, evo:
`evo_ape --align --correct_scale --n_to_align --align_origin`, `evo_rpe --delta_unit f|m
--all_pairs`). Written from the definitions (Umeyama 1991), not copied from evo.

  bench/evo_reference_eval.py GROUNDTRUTH ESTIMATE --rgbdvo build/rgbdvo [--max-dt 0.02]

Runs every alignment (se3, sim3, scale, origin, none; all poses and the first 40) with RPE steps
of 10 frames and 0.2 m, prints both figures (ATE rmse, scale, RPE translation rmse and pair
count) and exits 1 if any differs by more than 2%. Uses the TUM reader and association of
bench/tum_reference_eval.py. Needs python3-numpy (Debian).
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tum_reference_eval import associate, read_tum  # noqa: E402


def umeyama(x, y, with_scale):
    """R, t, c minimising sum |y_k - (c R x_k + t)|^2 for 3xN arrays (Umeyama 1991)."""
    mx, my = x.mean(axis=1, keepdims=True), y.mean(axis=1, keepdims=True)
    var_x = np.mean(np.sum((x - mx) ** 2, axis=0))
    u, d, vt = np.linalg.svd((y - my) @ (x - mx).T / x.shape[1])
    s = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        s[2, 2] = -1
    rot = u @ s @ vt
    c = np.trace(np.diag(d) @ s) / var_x if with_scale else 1.0
    return rot, my - c * rot @ mx, c


def ape(gt, est, max_dt, mode, n):
    """Matched poses (Q, aligned P), the scale and the ATE rmse, as evo aligns."""
    pairs = associate(sorted(gt), sorted(est), max_dt)
    q = np.array([gt[g] for g, _ in pairs])
    p = np.array([est[e] for _, e in pairs])
    c = 1.0
    if mode in ("se3", "sim3", "scale"):
        k = len(p) if n <= 0 else n
        rot, trans, c = umeyama(p[:k, :3, 3].T, q[:k, :3, 3].T, mode != "se3")
        p[:, :3, 3] *= c
        if mode != "scale":
            t = np.eye(4)
            t[:3, :3], t[:3, 3] = rot, trans[:, 0]
            p = t @ p
    elif mode == "origin":
        p = (q[0] @ np.linalg.inv(p[0])) @ p
    err = np.linalg.norm(p[:, :3, 3] - q[:, :3, 3], axis=1)
    return q, p, c, float(np.sqrt(np.mean(err * err)))


def rpe(q, p, unit, delta):
    """Translation rmse of E = (P_j^-1 P_i)^-1 (Q_j^-1 Q_i) over evo's all_pairs selection."""
    n = len(p)
    if unit == "frames":
        pairs = [(i, i + delta) for i in range(n - delta)]
    else:  # path length along the ground truth, nearest to delta, within 10%
        path = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(q[:, :3, 3], axis=0),
                                                               axis=1))])
        pairs = []
        for i in range(n - 1):
            ahead = path[i + 1:] - path[i]
            j = int(np.argmin(np.abs(ahead - delta)))
            if abs(ahead[j] - delta) <= 0.1 * delta:
                pairs.append((i, i + 1 + j))
    t = [np.linalg.norm(np.linalg.solve(np.linalg.solve(p[j], p[i]),
                                        np.linalg.solve(q[j], q[i]))[:3, 3]) for i, j in pairs]
    return float(np.sqrt(np.mean(np.square(t)))), len(t)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("groundtruth")
    ap.add_argument("estimate")
    ap.add_argument("--rgbdvo", required=True, help="rgbdvo executable")
    ap.add_argument("--max-dt", type=float, default=0.02)
    a = ap.parse_args()
    gt, est = read_tum(a.groundtruth), read_tum(a.estimate)
    worst = 0.0
    print(f"{'align':7s} {'first':>5s} {'step':>9s} {'ATE ref':>10s} {'rgbdvo':>10s} "
          f"{'scale ref':>9s} {'rgbdvo':>9s} {'RPE ref':>10s} {'rgbdvo':>10s} pairs")
    for mode in ("se3", "sim3", "scale", "origin", "none"):
        for n in (0, 40):
            if n and mode in ("origin", "none"):
                continue
            for unit, delta in (("frames", 10), ("m", 0.2)):
                q, p, c, ate = ape(gt, dict(est), a.max_dt, mode, n)
                rpe_t, pairs = rpe(q, p, unit, delta)
                out = subprocess.run(
                    [a.rgbdvo, "eval", a.groundtruth, a.estimate, "--max-dt", str(a.max_dt),
                     "--align", mode, "--align-first", str(n), "--delta", str(delta),
                     "--delta-unit", unit, "--json"],
                    check=True, capture_output=True, text=True).stdout
                r = json.loads(out)
                ours = (r["ate"]["error_m"]["rmse"], r["ate"]["scale"] or 1.0,
                        r["rpe"]["trans_m"]["rmse"])
                for ref, got in zip((ate, c, rpe_t), ours):
                    worst = max(worst, abs(got - ref) / max(abs(ref), 1e-12))
                if r["rpe"]["pairs"] != pairs:
                    worst = max(worst, 1.0)
                print(f"{mode:7s} {n:5d} {str(delta) + unit[0]:>9s} {ate:10.7f} {ours[0]:10.7f} "
                      f"{c:9.6f} {ours[1]:9.6f} {rpe_t:10.7f} {ours[2]:10.7f} "
                      f"{pairs}/{r['rpe']['pairs']}")
    print(f"largest relative difference: {100 * worst:.6f}% (limit 2%)")
    return 0 if worst <= 0.02 else 1


if __name__ == "__main__":
    sys.exit(main())
