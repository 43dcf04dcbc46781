#pragma once
// Trajectory error against ground truth, by default as defined by the TUM RGB-D benchmark (Sturm
// et al., IROS 2012): the absolute trajectory error after a rigid alignment (ATE,
// `evaluate_ate.py`) and the relative pose error over a fixed time step (RPE, `evaluate_rpe.py
// --fixed_delta --delta 1 --delta_unit s`). The options of evo's `ape` and `rpe` are available
// too: other alignments (with scale, scale only, first pose, none), a clock offset, and steps
// in frames or metres.

#include <string>
#include <utility>
#include <vector>

#include "rgbdvo/io/trajectory_io.hpp"

namespace rgbdvo {

// How the estimate is brought onto the ground truth before the ATE (evo's `ape` options).
enum class Alignment {
  kSe3,     // rigid, least squares (Horn 1987; Umeyama 1991 with c = 1): the TUM benchmark's ATE
  kSim3,    // rigid and a scale, least squares (Umeyama 1991): evo `--align --correct_scale`
  kScale,   // the scale of kSim3 only, positions multiplied about the origin: evo `--correct_scale`
  kOrigin,  // the first matched estimate pose put onto its ground truth pose: evo `--align_origin`
  kNone,    // raw: both in their own world frames
};
const char* AlignmentName(Alignment align);         // "se3", "sim3", "scale", "origin", "none"
Alignment ParseAlignment(const std::string& name);  // throws naming the value and the choices

// Unit of the RPE step.
enum class DeltaUnit {
  kSeconds,  // TUM `evaluate_rpe.py --fixed_delta`: the estimate pose nearest to t_i + delta
  kFrames,   // pairs (k, k + delta) of the time-matched sequence: evo `--delta_unit f --all_pairs`
  kMetres,   // pairs delta metres apart along the ground truth's path: evo `--delta_unit m
             // --all_pairs` (relative tolerance 0.1)
};
const char* DeltaUnitName(DeltaUnit unit);          // "s", "frames", "m"
DeltaUnit ParseDeltaUnit(const std::string& name);  // throws naming the value and the choices

struct EvaluationOptions {
  double max_dt_s = 0.02;             // largest ground truth-estimate time difference of a match, s
  double t_offset_s = 0;              // added to the estimate's timestamps before matching, s
  Alignment align = Alignment::kSe3;  // ATE alignment
  int align_first = 0;  // align on the first N matched poses only; 0 = all (evo `--n_to_align`)
  double delta = 1.0;   // RPE step between the two poses of a pair, in delta_unit
  DeltaUnit delta_unit = DeltaUnit::kSeconds;
  void Check() const;  // throws naming the field
};

// The RPE step in words: "1 s apart", "5 frames apart", "0.5 m apart along the ground truth".
std::string DescribeDelta(const EvaluationOptions& options);

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
  std::string reason;  // why not, when !success
  int matched = 0;     // poses matched: estimate poses paired with a ground truth pose in time
  int aligned_on = 0;  // matched poses the alignment was fitted to (align_first; 1 for origin)
  Alignment align = Alignment::kSe3;
  // p_gt ~ gt_from_est * (scale * p_est): the scale (kSim3, kScale; else 1) multiplies the
  // estimate's positions about its origin, then the rigid part (identity for kScale and kNone).
  Rigid3d gt_from_est = Rigid3d::Identity();
  double scale = 1;
  ErrorStats error_m;  // |gt_from_est * (scale * t_est) - t_gt| over the matched poses
  std::vector<double> pose_times_s;   // per matched pose in time order: estimate time + t_offset
  std::vector<double> pose_errors_m;  // per matched pose: its position error
  Rigid3d Aligned(const Rigid3d& world_from_cam) const;  // an estimate pose in the gt's frame
  std::string Brief() const;
};

// ATE: positions matched by AssociateByTime (estimate timestamps + t_offset), the estimate
// brought onto the ground truth by options.align fitted to the first align_first matches, the
// position error of every match. success=false with a reason for fewer than 3 matches (1 for
// kOrigin and kNone), a scale that cannot be fitted (an estimate that does not move) or errors
// that are not finite (coordinates so large that an error or its square overflows).
// ComputeAte and ComputeRpe take the ground truth sorted by time with unique timestamps (as
// ReadTrajectory returns it); the estimate in any order, of repeated times the last pose counts.
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

// RPE over pose pairs one step apart, E = (P_j^-1 P_i)^-1 (Q_j^-1 Q_i) for estimate poses
// P_i, P_j and ground truth poses Q_i, Q_j, the estimate's translations multiplied by `scale`
// first (the ATE's scale for kSim3 and kScale: evo's RPE is computed after its alignment too).
// The estimate's timestamps are shifted by t_offset. The pairs, by delta_unit:
// - kSeconds (TUM): for every estimate pose i, j is the estimate pose nearest in time to
//   t_i + delta (pairs with j the last pose are dropped); Q_i, Q_j are the ground truth poses
//   nearest in time to t_i, t_j (the pair is skipped when either is further than twice the
//   ground truth's median sampling interval).
// - kFrames: the poses matched by AssociateByTime in time order, pairs (k, k + delta).
// - kMetres: the same matched sequence; for every k, the l > k whose ground truth path length
//   from k is nearest to delta, kept when within 10% of delta.
// success=false with a reason for no pair or errors that are not finite (as ComputeAte).
RpeResult ComputeRpe(const std::vector<StampedPose>& groundtruth,
                     const std::vector<StampedPose>& estimate, const EvaluationOptions& options,
                     double scale = 1.0);

}  // namespace rgbdvo
