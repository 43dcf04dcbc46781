#!/usr/bin/python3
"""Independent numpy re-implementation of the TUM RGB-D benchmark's trajectory errors, to
cross-check `rgbdvo eval` (Sturm et al., IROS 2012; the tools `evaluate_ate.py` and
`evaluate_rpe.py --fixed_delta --delta 1 --delta_unit s`). Written from the definitions, not
copied from the tools.

  bench/tum_reference_eval.py GROUNDTRUTH ESTIMATE [--max-dt 0.02] [--delta 1] [--json]
  bench/tum_reference_eval.py GROUNDTRUTH ESTIMATE --rgbdvo build/rgbdvo

With --rgbdvo it also runs `rgbdvo eval --json` on the same files, prints both figures and their
relative difference, and exits 1 if any differs by more than 2%.

Files: TUM format, `timestamp tx ty tz qx qy qz qw` per line, '#' comments (camera-to-world).
Needs python3-numpy (Debian).
"""
import argparse
import json
import subprocess
import sys

import numpy as np


def read_tum(path):
    """Dict timestamp -> 4x4 camera-to-world pose."""
    poses = {}
    with open(path) as f:
        for line in f:
            fields = line.replace(",", " ").split()
            if not fields or fields[0].startswith("#"):
                continue
            t, x, y, z, qx, qy, qz, qw = (float(v) for v in fields[:8])
            q = np.array([qw, qx, qy, qz]) / np.linalg.norm([qw, qx, qy, qz])
            w, a, b, c = q
            rot = np.array([
                [1 - 2 * (b * b + c * c), 2 * (a * b - c * w), 2 * (a * c + b * w)],
                [2 * (a * b + c * w), 1 - 2 * (a * a + c * c), 2 * (b * c - a * w)],
                [2 * (a * c - b * w), 2 * (b * c + a * w), 1 - 2 * (a * a + b * b)],
            ])
            pose = np.eye(4)
            pose[:3, :3] = rot
            pose[:3, 3] = [x, y, z]
            poses[t] = pose
    if not poses:
        sys.exit(f"{path}: no poses")
    return poses


def associate(gt_stamps, est_stamps, max_dt):
    """Unique (gt, est) timestamp pairs within max_dt, the closest pairs taken first."""
    candidates = sorted(
        (abs(g - e), g, e) for e in est_stamps for g in gt_stamps if abs(g - e) < max_dt)
    used_g, used_e, pairs = set(), set(), []
    for _, g, e in candidates:
        if g not in used_g and e not in used_e:
            used_g.add(g)
            used_e.add(e)
            pairs.append((g, e))
    return sorted(pairs, key=lambda p: p[1])


def horn_align(model, data):
    """Rotation and translation with data ~ rot @ model + trans (3xN arrays), no scale."""
    mu_m = model.mean(axis=1, keepdims=True)
    mu_d = data.mean(axis=1, keepdims=True)
    cross = (data - mu_d) @ (model - mu_m).T  # sum of d_k m_k^T
    u, _, vt = np.linalg.svd(cross)
    fix = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        fix[2, 2] = -1
    rot = u @ fix @ vt
    return rot, mu_d - rot @ mu_m


def stats(values):
    v = np.asarray(values, dtype=float)
    return {"rmse": float(np.sqrt(np.mean(v * v))), "mean": float(np.mean(v)),
            "median": float(np.median(v)), "max": float(np.max(v)), "count": int(v.size)}


def ate(gt, est, max_dt):
    pairs = associate(sorted(gt), sorted(est), max_dt)
    if len(pairs) < 3:
        sys.exit("too few matched poses for ATE")
    data = np.array([gt[g][:3, 3] for g, _ in pairs]).T
    model = np.array([est[e][:3, 3] for _, e in pairs]).T
    rot, trans = horn_align(model, data)
    err = np.linalg.norm(rot @ model + trans - data, axis=0)
    return stats(err), len(pairs)


def closest(sorted_stamps, t):
    i = int(np.searchsorted(sorted_stamps, t))
    if i == 0:
        return 0
    if i == len(sorted_stamps):
        return i - 1
    return i - 1 if t - sorted_stamps[i - 1] <= sorted_stamps[i] - t else i


def rotation_angle(rot):
    return float(np.arccos(np.clip((np.trace(rot) - 1) / 2, -1.0, 1.0)))


def rpe(gt, est, delta):
    gt_t = np.array(sorted(gt))
    est_t = np.array(sorted(est))
    max_gt_dt = 2 * float(np.median(np.diff(gt_t)))
    trans, rot = [], []
    for i in range(len(est_t)):
        j = closest(est_t, est_t[i] + delta)
        if j == len(est_t) - 1:
            continue
        gi, gj = closest(gt_t, est_t[i]), closest(gt_t, est_t[j])
        if abs(gt_t[gi] - est_t[i]) > max_gt_dt or abs(gt_t[gj] - est_t[j]) > max_gt_dt:
            continue
        p_rel = np.linalg.solve(est[est_t[j]], est[est_t[i]])  # P_j^-1 P_i
        q_rel = np.linalg.solve(gt[gt_t[gj]], gt[gt_t[gi]])    # Q_j^-1 Q_i
        err = np.linalg.solve(p_rel, q_rel)                    # (P_j^-1 P_i)^-1 Q_j^-1 Q_i
        trans.append(float(np.linalg.norm(err[:3, 3])))
        rot.append(np.degrees(rotation_angle(err[:3, :3])))
    if not trans:
        sys.exit("no RPE pairs")
    return stats(trans), stats(rot), len(trans)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("groundtruth")
    ap.add_argument("estimate")
    ap.add_argument("--max-dt", type=float, default=0.02)
    ap.add_argument("--delta", type=float, default=1.0)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--rgbdvo", help="rgbdvo executable: compare with `rgbdvo eval --json`")
    a = ap.parse_args()
    gt, est = read_tum(a.groundtruth), read_tum(a.estimate)
    ate_m, matched = ate(gt, est, a.max_dt)
    rpe_t, rpe_r, pairs = rpe(gt, est, a.delta)
    ref = {"ate_rmse_m": ate_m["rmse"], "ate_mean_m": ate_m["mean"],
           "ate_median_m": ate_m["median"], "ate_max_m": ate_m["max"], "ate_matched": matched,
           "rpe_trans_rmse_m": rpe_t["rmse"], "rpe_trans_mean_m": rpe_t["mean"],
           "rpe_trans_median_m": rpe_t["median"], "rpe_rot_rmse_deg": rpe_r["rmse"],
           "rpe_rot_mean_deg": rpe_r["mean"], "rpe_rot_median_deg": rpe_r["median"],
           "rpe_pairs": pairs}
    if not a.rgbdvo:
        if a.json:
            print(json.dumps(ref))
        else:
            for k, v in ref.items():
                print(f"{k:20s} {v:.6g}")
        return 0
    out = subprocess.run([a.rgbdvo, "eval", a.groundtruth, a.estimate, "--max-dt", str(a.max_dt),
                          "--delta", str(a.delta), "--json"], check=True, capture_output=True,
                         text=True).stdout
    r = json.loads(out)
    ours = {"ate_rmse_m": r["ate"]["error_m"]["rmse"], "ate_mean_m": r["ate"]["error_m"]["mean"],
            "ate_median_m": r["ate"]["error_m"]["median"], "ate_max_m": r["ate"]["error_m"]["max"],
            "ate_matched": r["ate"]["matched"],
            "rpe_trans_rmse_m": r["rpe"]["trans_m"]["rmse"],
            "rpe_trans_mean_m": r["rpe"]["trans_m"]["mean"],
            "rpe_trans_median_m": r["rpe"]["trans_m"]["median"],
            "rpe_rot_rmse_deg": r["rpe"]["rot_deg"]["rmse"],
            "rpe_rot_mean_deg": r["rpe"]["rot_deg"]["mean"],
            "rpe_rot_median_deg": r["rpe"]["rot_deg"]["median"], "rpe_pairs": r["rpe"]["pairs"]}
    worst = 0.0
    print(f"{'figure':20s} {'reference':>12s} {'rgbdvo':>12s} {'rel. diff':>10s}")
    for k in ref:
        diff = abs(ours[k] - ref[k]) / max(abs(ref[k]), 1e-12)
        worst = max(worst, diff)
        print(f"{k:20s} {ref[k]:12.6g} {ours[k]:12.6g} {100 * diff:9.4f}%")
    print(f"largest relative difference: {100 * worst:.4f}% (limit 2%)")
    return 0 if worst <= 0.02 else 1


if __name__ == "__main__":
    sys.exit(main())
