#pragma once
// Trajectory error against ground truth, as defined by the TUM RGB-D benchmark (Sturm et al.,
// IROS 2012): the absolute trajectory error (ATE, `evaluate_ate.py`) and the relative pose error
// over a fixed time step (RPE, `evaluate_rpe.py --fixed_delta --delta 1 --delta_unit s`).

#include <string>
#include <utility>
#include <vector>

#include "rgbdvo/io/trajectory_io.hpp"

namespace rgbdvo {

struct EvaluationOptions {
  double max_dt_s = 0.02;  // ATE: largest ground truth-estimate time difference of a match, s
  double delta_s = 1.0;    // RPE: time step between the two poses of a pair, s
  void Check() const;      // throws naming the field
};

// RMSE, mean, median and max of a list of non-negative errors (all 0 when empty).
struct ErrorStats {
  int count = 0;
  double rmse = 0, mean = 0, median = 0, max = 0;
};
ErrorStats ComputeStats(std::vector<double> errors);

// Pairs (ground truth index, estimate index) with |t_gt - t_est| <= max_dt, each pose used at
// most once, closest pairs first (TUM `associate.py`). Sorted by estimate index.
std::vector<std::pair<int, int>> AssociateByTime(const std::vector<StampedPose>& groundtruth,
                                                 const std::vector<StampedPose>& estimate,
                                                 double max_dt_s);

struct AteResult {
  bool success = false;
  std::string reason;                         // why not, when !success
  int matched = 0;                            // associated pose pairs
  Rigid3d gt_from_est = Rigid3d::Identity();  // p_gt ~ gt_from_est * p_est (no scale)
  ErrorStats error_m;                         // |gt_from_est * t_est - t_gt| over the matches
  std::string Brief() const;
};

// ATE: positions matched by AssociateByTime, the estimate aligned to the ground truth by the
// closed-form least-squares rigid fit without scale (Horn 1987; Umeyama 1991 with c = 1).
// success=false with a reason for fewer than 3 matches.
AteResult ComputeAte(const std::vector<StampedPose>& groundtruth,
                     const std::vector<StampedPose>& estimate, const EvaluationOptions& options);

struct RpeResult {
  bool success = false;
  std::string reason;
  int pairs = 0;       // pose pairs used
  ErrorStats trans_m;  // |translation(E)|, m per delta
  ErrorStats rot_deg;  // rotation angle of E, degrees per delta
  std::string Brief() const;
};

// Both take trajectories sorted by timestamp, as ReadTrajectory returns them.
// RPE over a fixed time step: for every estimate pose i, j is the estimate pose nearest in time
// to t_i + delta (pairs with j the last pose are dropped); Q_i, Q_j are the ground truth poses
// nearest in time to t_i, t_j (the pair is skipped when either is further than twice the ground
// truth's median sampling interval); E = (P_j^-1 P_i)^-1 (Q_j^-1 Q_i).
RpeResult ComputeRpe(const std::vector<StampedPose>& groundtruth,
                     const std::vector<StampedPose>& estimate, const EvaluationOptions& options);

struct EvaluationReport {
  std::string groundtruth_path, estimate_path;
  int groundtruth_poses = 0, estimate_poses = 0;
  int groundtruth_repeated = 0, estimate_repeated = 0;  // rows with a repeated timestamp, dropped
  EvaluationOptions options;
  AteResult ate;
  RpeResult rpe;
  std::string Table() const;  // a short human-readable table
  std::string Json() const;   // one JSON object
};

// Reads both files and computes ATE and RPE. Throws for unreadable files and when no estimate
// pose has a ground truth pose within max_dt (no overlapping timestamps).
EvaluationReport EvaluateFiles(const std::string& groundtruth_path,
                               const std::string& estimate_path, const EvaluationOptions& options);

}  // namespace rgbdvo
