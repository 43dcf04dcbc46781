#include "rgbdvo/evaluation/evaluation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace rgbdvo {
namespace {

// Index of the time in `stamps` (sorted) nearest to t.
size_t NearestIndex(const std::vector<double>& stamps, double t) {
  const auto it = std::lower_bound(stamps.begin(), stamps.end(), t);
  if (it == stamps.begin()) return 0;
  if (it == stamps.end()) return stamps.size() - 1;
  const size_t hi = static_cast<size_t>(it - stamps.begin());
  return (t - stamps[hi - 1] <= stamps[hi] - t) ? hi - 1 : hi;
}

std::vector<double> Stamps(const std::vector<StampedPose>& poses) {
  std::vector<double> s;
  s.reserve(poses.size());
  for (const StampedPose& p : poses) s.push_back(p.timestamp);
  return s;
}

// The estimate as evaluated: timestamps shifted by t_offset, the last of repeated times kept.
std::vector<StampedPose> Shifted(const std::vector<StampedPose>& est, double t_offset_s) {
  std::vector<StampedPose> out = est;
  for (StampedPose& p : out) p.timestamp += t_offset_s;
  KeepLastOfEachTime(&out);
  return out;
}

bool Finite(const ErrorStats& s) {
  return std::isfinite(s.rmse) && std::isfinite(s.mean) && std::isfinite(s.median) &&
         std::isfinite(s.max);
}

// Why the statistics of `errors` (what: "position error") are not finite, or "" when they are:
// coordinates so large that an error or its square overflows.
std::string NonFiniteReason(const std::vector<double>& errors, const ErrorStats& stats,
                            const std::string& what, const std::vector<double>& times) {
  for (size_t k = 0; k < errors.size(); ++k) {
    if (std::isfinite(errors[k])) continue;
    std::ostringstream why;
    why << std::fixed << std::setprecision(6) << what << " not finite";
    if (k < times.size()) why << " at estimate time " << times[k];
    return why.str() + " (coordinates too large to compute with)";
  }
  if (!Finite(stats))
    return what + " statistics not finite (coordinates too large to compute with)";
  return "";
}

}  // namespace

std::string DescribeDelta(const EvaluationOptions& o) {
  std::ostringstream d;
  d << o.delta;
  switch (o.delta_unit) {
    case DeltaUnit::kSeconds:
      return d.str() + " s apart";
    case DeltaUnit::kFrames:
      return d.str() + " frames apart";
    case DeltaUnit::kMetres:
      return d.str() + " m apart along the ground truth";
  }
  return d.str();
}

const char* AlignmentName(Alignment align) {
  switch (align) {
    case Alignment::kSe3:
      return "se3";
    case Alignment::kSim3:
      return "sim3";
    case Alignment::kScale:
      return "scale";
    case Alignment::kOrigin:
      return "origin";
    case Alignment::kNone:
      return "none";
  }
  return "?";
}

Alignment ParseAlignment(const std::string& name) {
  for (const Alignment a :
       {Alignment::kSe3, Alignment::kSim3, Alignment::kScale, Alignment::kOrigin, Alignment::kNone})
    if (name == AlignmentName(a)) return a;
  throw std::invalid_argument("alignment '" + name +
                              "' is not one of se3, sim3, scale, origin, none");
}

const char* DeltaUnitName(DeltaUnit unit) {
  switch (unit) {
    case DeltaUnit::kSeconds:
      return "s";
    case DeltaUnit::kFrames:
      return "frames";
    case DeltaUnit::kMetres:
      return "m";
  }
  return "?";
}

DeltaUnit ParseDeltaUnit(const std::string& name) {
  for (const DeltaUnit u : {DeltaUnit::kSeconds, DeltaUnit::kFrames, DeltaUnit::kMetres})
    if (name == DeltaUnitName(u)) return u;
  throw std::invalid_argument("delta unit '" + name + "' is not one of s, frames, m");
}

void EvaluationOptions::Check() const {
  if (!(max_dt_s > 0 && std::isfinite(max_dt_s)))
    throw std::invalid_argument("EvaluationOptions.max_dt_s must be a finite number > 0 s");
  if (!std::isfinite(t_offset_s))
    throw std::invalid_argument("EvaluationOptions.t_offset_s must be a finite number of s");
  if (!(delta > 0 && std::isfinite(delta)))
    throw std::invalid_argument("EvaluationOptions.delta must be a finite number > 0");
  if (delta_unit == DeltaUnit::kFrames && delta != std::floor(delta))
    throw std::invalid_argument("EvaluationOptions.delta must be a whole number of frames");
  if (align_first < 0 || align_first == 1 || align_first == 2)
    throw std::invalid_argument(
        "EvaluationOptions.align_first must be 0 (all) or at least 3 poses (a fit needs 3)");
}

ErrorStats ComputeStats(std::vector<double> e) {
  ErrorStats s;
  s.count = static_cast<int>(e.size());
  if (e.empty()) return s;
  double sum = 0, sum_sq = 0;
  for (const double x : e) {
    sum += x;
    sum_sq += x * x;
    s.max = std::max(s.max, x);
  }
  s.mean = sum / e.size();
  s.rmse = std::sqrt(sum_sq / e.size());
  std::sort(e.begin(), e.end());
  const size_t n = e.size();
  s.median = n % 2 ? e[n / 2] : 0.5 * (e[n / 2 - 1] + e[n / 2]);
  return s;
}

std::vector<std::pair<int, int>> AssociateByTime(const std::vector<StampedPose>& gt,
                                                 const std::vector<StampedPose>& est,
                                                 double max_dt_s) {
  // Every candidate pair within max_dt, then greedily the closest ones with both poses unused.
  const std::vector<double> gt_stamps = Stamps(gt);
  struct Candidate {
    double dt;
    int g, e;
  };
  std::vector<Candidate> candidates;
  for (size_t e = 0; e < est.size(); ++e) {
    const double t = est[e].timestamp;
    auto it = std::lower_bound(gt_stamps.begin(), gt_stamps.end(), t - max_dt_s);
    for (; it != gt_stamps.end() && *it <= t + max_dt_s; ++it)
      candidates.push_back(
          {std::abs(*it - t), static_cast<int>(it - gt_stamps.begin()), static_cast<int>(e)});
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.dt < b.dt; });
  std::vector<bool> gt_used(gt.size(), false), est_used(est.size(), false);
  std::vector<std::pair<int, int>> matches;
  for (const Candidate& c : candidates) {
    if (gt_used[c.g] || est_used[c.e]) continue;
    gt_used[c.g] = est_used[c.e] = true;
    matches.emplace_back(c.g, c.e);
  }
  std::sort(matches.begin(), matches.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  return matches;
}

Rigid3d AteResult::Aligned(const Rigid3d& world_from_cam) const {
  Rigid3d scaled = world_from_cam;
  scaled.translation() *= scale;
  return gt_from_est * scaled;
}

AteResult ComputeAte(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& estimate,
                     const EvaluationOptions& options) {
  options.Check();
  AteResult r;
  r.align = options.align;
  const std::vector<StampedPose> est = Shifted(estimate, options.t_offset_s);
  const auto matches = AssociateByTime(gt, est, options.max_dt_s);
  r.matched = static_cast<int>(matches.size());
  const bool fitted = options.align == Alignment::kSe3 || options.align == Alignment::kSim3 ||
                      options.align == Alignment::kScale;
  const int need = fitted ? 3 : 1;
  if (r.matched < need) {
    r.reason = "only " + std::to_string(r.matched) + " poses matched in time (need " +
               std::to_string(need) + ")";
    return r;
  }
  Eigen::Matrix3Xd p_est(3, r.matched), p_gt(3, r.matched);
  for (int k = 0; k < r.matched; ++k) {
    p_gt.col(k) = gt[matches[k].first].world_from_cam.translation();
    p_est.col(k) = est[matches[k].second].world_from_cam.translation();
  }
  r.aligned_on = !fitted                   ? (options.align == Alignment::kOrigin ? 1 : 0)
                 : options.align_first > 0 ? std::min(options.align_first, r.matched)
                                           : r.matched;
  if (fitted) {
    // Umeyama (1991): R from the SVD of the centred cross-covariance with the reflection case
    // corrected, the scale c = trace(D S) / var(p_est) when asked for, t from the centroids.
    // Without scale it is the same minimiser as Horn (1987).
    const bool with_scale = options.align != Alignment::kSe3;
    const Eigen::Matrix4d m =
        r.aligned_on == r.matched
            ? Eigen::Matrix4d(Eigen::umeyama(p_est, p_gt, with_scale))
            : Eigen::Matrix4d(Eigen::umeyama(p_est.leftCols(r.aligned_on),
                                             p_gt.leftCols(r.aligned_on), with_scale));
    if (!with_scale) {
      r.gt_from_est.matrix() = m;
    } else {
      r.scale = m.block<3, 3>(0, 0).col(0).norm();  // the columns of c R have length c
      if (!(std::isfinite(r.scale) && r.scale > 1e-12)) {
        r.reason = "no scale: the estimate does not move over the poses aligned on";
        r.scale = 1;
        return r;
      }
      if (options.align == Alignment::kSim3) {
        r.gt_from_est.linear() = m.block<3, 3>(0, 0) / r.scale;
        r.gt_from_est.translation() = m.block<3, 1>(0, 3);
      }
    }
  } else if (options.align == Alignment::kOrigin) {
    // The whole first pose, rotation too: gt_from_est * P_0 = Q_0.
    r.gt_from_est =
        gt[matches[0].first].world_from_cam * est[matches[0].second].world_from_cam.inverse();
  }
  r.pose_times_s.resize(r.matched);
  r.pose_errors_m.resize(r.matched);
  for (int k = 0; k < r.matched; ++k) {
    r.pose_times_s[k] = est[matches[k].second].timestamp;
    r.pose_errors_m[k] = (r.gt_from_est * (r.scale * p_est.col(k)) - p_gt.col(k)).norm();
  }
  r.error_m = ComputeStats(r.pose_errors_m);
  r.reason = NonFiniteReason(r.pose_errors_m, r.error_m, "position error", r.pose_times_s);
  r.success = r.reason.empty();
  return r;
}

namespace {

// Pairs (i, j) of estimate indices and their ground truth poses (gi, gj).
struct RpePair {
  size_t i, j, gi, gj;
};

// TUM `evaluate_rpe.py --fixed_delta`: see ComputeRpe.
std::vector<RpePair> PairsBySeconds(const std::vector<StampedPose>& gt,
                                    const std::vector<StampedPose>& est, double delta_s) {
  const std::vector<double> gt_stamps = Stamps(gt), est_stamps = Stamps(est);
  std::vector<double> intervals;
  for (size_t k = 1; k < gt_stamps.size(); ++k)
    intervals.push_back(gt_stamps[k] - gt_stamps[k - 1]);
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  double median_interval = intervals[intervals.size() / 2];
  if (intervals.size() % 2 == 0) {  // numpy.median: mean of the two middle values
    const double lower =
        *std::max_element(intervals.begin(), intervals.begin() + intervals.size() / 2);
    median_interval = 0.5 * (median_interval + lower);
  }
  const double max_gt_dt = 2 * median_interval;
  std::vector<RpePair> pairs;
  for (size_t i = 0; i < est.size(); ++i) {
    const size_t j = NearestIndex(est_stamps, est_stamps[i] + delta_s);
    if (j == est.size() - 1) continue;
    const size_t gi = NearestIndex(gt_stamps, est_stamps[i]);
    const size_t gj = NearestIndex(gt_stamps, est_stamps[j]);
    if (std::abs(gt_stamps[gi] - est_stamps[i]) > max_gt_dt ||
        std::abs(gt_stamps[gj] - est_stamps[j]) > max_gt_dt)
      continue;
    pairs.push_back({i, j, gi, gj});
  }
  return pairs;
}

// Pairs of the time-matched sequence `m` (gt index, estimate index) k steps apart, or delta
// metres apart along the ground truth's path through the matched poses (within 10%).
std::vector<RpePair> PairsOfMatches(const std::vector<StampedPose>& gt,
                                    const std::vector<std::pair<int, int>>& m,
                                    const EvaluationOptions& o) {
  std::vector<RpePair> pairs;
  const auto pair = [&](size_t k, size_t l) {
    pairs.push_back(
        {size_t(m[k].second), size_t(m[l].second), size_t(m[k].first), size_t(m[l].first)});
  };
  if (o.delta_unit == DeltaUnit::kFrames) {
    const size_t step = static_cast<size_t>(o.delta);
    for (size_t k = 0; k + step < m.size(); ++k) pair(k, k + step);
    return pairs;
  }
  std::vector<double> path(m.size(), 0.0);  // ground truth path length from the first match
  for (size_t k = 1; k < m.size(); ++k)
    path[k] = path[k - 1] + (gt[m[k].first].world_from_cam.translation() -
                             gt[m[k - 1].first].world_from_cam.translation())
                                .norm();
  for (size_t k = 0; k + 1 < m.size(); ++k) {
    // path is non-decreasing: the nearest to path[k] + delta is at the lower bound or before.
    const auto it = std::lower_bound(path.begin() + k + 1, path.end(), path[k] + o.delta);
    size_t l = static_cast<size_t>(it - path.begin());
    if (l == m.size() ||
        (l > k + 1 && path[k] + o.delta - path[l - 1] <= path[l] - path[k] - o.delta))
      --l;
    if (std::abs(path[l] - path[k] - o.delta) <= 0.1 * o.delta) pair(k, l);
  }
  return pairs;
}

}  // namespace

RpeResult ComputeRpe(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& estimate,
                     const EvaluationOptions& options, double scale) {
  options.Check();
  RpeResult r;
  if (gt.size() < 2 || estimate.size() < 2) {
    r.reason = "need at least 2 poses in each trajectory";
    return r;
  }
  const std::vector<StampedPose> est = Shifted(estimate, options.t_offset_s);
  std::vector<std::pair<int, int>> matches;
  std::vector<RpePair> pairs;
  if (options.delta_unit == DeltaUnit::kSeconds) {
    pairs = PairsBySeconds(gt, est, options.delta);
  } else {
    matches = AssociateByTime(gt, est, options.max_dt_s);
    pairs = PairsOfMatches(gt, matches, options);
  }
  std::vector<double> trans, rot;
  for (const RpePair& p : pairs) {
    Rigid3d est_j_from_i = est[p.j].world_from_cam.inverse() * est[p.i].world_from_cam;
    est_j_from_i.translation() *= scale;
    const Rigid3d gt_j_from_i = gt[p.gj].world_from_cam.inverse() * gt[p.gi].world_from_cam;
    const Rigid3d E = est_j_from_i.inverse() * gt_j_from_i;
    trans.push_back(E.translation().norm());
    rot.push_back(RotationAngleDeg(E.linear()));
  }
  r.pairs = static_cast<int>(trans.size());
  r.trans_m = ComputeStats(trans);
  r.rot_deg = ComputeStats(rot);
  r.success = r.pairs > 0;
  if (r.success) {
    std::vector<double> times;
    times.reserve(pairs.size());
    for (const RpePair& p : pairs) times.push_back(est[p.i].timestamp);
    r.reason = NonFiniteReason(trans, r.trans_m, "relative translation error", times);
    if (r.reason.empty())
      r.reason = NonFiniteReason(rot, r.rot_deg, "relative rotation error", times);
    r.success = r.reason.empty();
  } else {
    std::ostringstream why;
    why << "no pose pairs " << DescribeDelta(options);
    if (options.delta_unit == DeltaUnit::kSeconds)
      why << " with ground truth (estimate spans " << est.back().timestamp - est.front().timestamp
          << " s)";
    else
      why << " among " << matches.size() << " poses matched";
    r.reason = why.str();
  }
  return r;
}

std::string AteResult::Brief() const {
  if (!success) return "ATE: n/a (" + reason + ")";
  std::ostringstream s;
  s << std::fixed << std::setprecision(4) << "ATE: rmse " << error_m.rmse << " m, mean "
    << error_m.mean << " m, median " << error_m.median << " m, max " << error_m.max << " m over "
    << matched << " poses matched";
  return s.str();
}

std::string RpeResult::Brief() const {
  if (!success) return "RPE: n/a (" + reason + ")";
  std::ostringstream s;
  s << std::fixed << std::setprecision(4) << "RPE: rmse " << trans_m.rmse << " m, "
    << std::setprecision(3) << rot_deg.rmse << " deg per delta over " << pairs << " pairs";
  return s.str();
}

}  // namespace rgbdvo
