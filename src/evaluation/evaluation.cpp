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

std::string JsonString(const std::string& s) {
  std::ostringstream out;
  out << '"';
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << static_cast<int>(c)
          << std::dec << std::setfill(' ');
    } else {
      out << c;
    }
  }
  return out.str() + '"';
}

// The statistics, or null for each when they could not be computed (no pose or pair): a reader
// must not mistake "not computed" for a perfect 0.
std::string JsonStats(const ErrorStats& s, bool computed) {
  std::ostringstream out;
  out << std::setprecision(9);
  const auto value = [&](double v) -> std::ostream& {
    return computed ? (out << v) : (out << "null");
  };
  out << "{\"rmse\": ";
  value(s.rmse) << ", \"mean\": ";
  value(s.mean) << ", \"median\": ";
  value(s.median) << ", \"max\": ";
  value(s.max) << "}";
  return out.str();
}

}  // namespace

void EvaluationOptions::Check() const {
  if (!(max_dt_s > 0)) throw std::invalid_argument("EvaluationOptions.max_dt_s must be > 0 s");
  if (!(delta_s > 0)) throw std::invalid_argument("EvaluationOptions.delta_s must be > 0 s");
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

AteResult ComputeAte(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& est,
                     const EvaluationOptions& options) {
  options.Check();
  AteResult r;
  const auto matches = AssociateByTime(gt, est, options.max_dt_s);
  r.matched = static_cast<int>(matches.size());
  if (r.matched < 3) {
    r.reason = "only " + std::to_string(r.matched) + " poses matched in time (need 3)";
    return r;
  }
  Eigen::Matrix3Xd p_est(3, r.matched), p_gt(3, r.matched);
  for (int k = 0; k < r.matched; ++k) {
    p_gt.col(k) = gt[matches[k].first].world_from_cam.translation();
    p_est.col(k) = est[matches[k].second].world_from_cam.translation();
  }
  // Umeyama (1991) without scale: R from the SVD of the centred cross-covariance with the
  // reflection case corrected, t from the centroids; the same minimiser as Horn (1987).
  r.gt_from_est.matrix() = Eigen::umeyama(p_est, p_gt, false);
  std::vector<double> errors(r.matched);
  for (int k = 0; k < r.matched; ++k)
    errors[k] = (r.gt_from_est * p_est.col(k) - p_gt.col(k)).norm();
  r.error_m = ComputeStats(errors);
  r.success = true;
  return r;
}

RpeResult ComputeRpe(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& est,
                     const EvaluationOptions& options) {
  options.Check();
  RpeResult r;
  if (gt.size() < 2 || est.size() < 2) {
    r.reason = "need at least 2 poses in each trajectory";
    return r;
  }
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

  std::vector<double> trans, rot;
  for (size_t i = 0; i < est.size(); ++i) {
    const size_t j = NearestIndex(est_stamps, est_stamps[i] + options.delta_s);
    if (j == est.size() - 1) continue;
    const size_t gi = NearestIndex(gt_stamps, est_stamps[i]);
    const size_t gj = NearestIndex(gt_stamps, est_stamps[j]);
    if (std::abs(gt_stamps[gi] - est_stamps[i]) > max_gt_dt ||
        std::abs(gt_stamps[gj] - est_stamps[j]) > max_gt_dt)
      continue;
    const Rigid3d est_j_from_i = est[j].world_from_cam.inverse() * est[i].world_from_cam;
    const Rigid3d gt_j_from_i = gt[gj].world_from_cam.inverse() * gt[gi].world_from_cam;
    const Rigid3d E = est_j_from_i.inverse() * gt_j_from_i;
    trans.push_back(E.translation().norm());
    rot.push_back(RotationAngleDeg(E.linear()));
  }
  r.pairs = static_cast<int>(trans.size());
  r.trans_m = ComputeStats(trans);
  r.rot_deg = ComputeStats(rot);
  r.success = r.pairs > 0;
  if (!r.success) {
    std::ostringstream why;
    why << "no pose pairs " << options.delta_s << " s apart with ground truth (estimate spans "
        << est_stamps.back() - est_stamps.front() << " s)";
    r.reason = why.str();
  }
  return r;
}

std::string AteResult::Brief() const {
  if (!success) return "ATE: n/a (" + reason + ")";
  std::ostringstream s;
  s << std::fixed << std::setprecision(4) << "ATE: rmse " << error_m.rmse << " m, mean "
    << error_m.mean << " m, median " << error_m.median << " m, max " << error_m.max << " m over "
    << matched << " poses";
  return s.str();
}

std::string RpeResult::Brief() const {
  if (!success) return "RPE: n/a (" + reason + ")";
  std::ostringstream s;
  s << std::fixed << std::setprecision(4) << "RPE: rmse " << trans_m.rmse << " m, "
    << std::setprecision(3) << rot_deg.rmse << " deg per delta over " << pairs << " pairs";
  return s.str();
}

EvaluationReport EvaluateFiles(const std::string& gt_path, const std::string& est_path,
                               const EvaluationOptions& options) {
  options.Check();
  const Trajectory gt = ReadTrajectory(gt_path);
  const Trajectory est = ReadTrajectory(est_path);
  EvaluationReport report;
  report.groundtruth_path = gt_path;
  report.estimate_path = est_path;
  report.groundtruth_poses = static_cast<int>(gt.poses.size());
  report.estimate_poses = static_cast<int>(est.poses.size());
  report.groundtruth_repeated = gt.repeated_timestamps;
  report.estimate_repeated = est.repeated_timestamps;
  report.options = options;
  report.ate = ComputeAte(gt.poses, est.poses, options);
  if (report.ate.matched == 0) {
    std::ostringstream msg;
    msg << std::fixed << std::setprecision(3) << est_path << ": no pose within " << options.max_dt_s
        << " s of a ground truth pose in " << gt_path << " (estimate spans "
        << est.poses.front().timestamp << ".." << est.poses.back().timestamp << " s, ground truth "
        << gt.poses.front().timestamp << ".." << gt.poses.back().timestamp
        << " s): no overlapping timestamps";
    throw std::runtime_error(msg.str());
  }
  report.rpe = ComputeRpe(gt.poses, est.poses, options);
  return report;
}

std::string EvaluationReport::Table() const {
  std::ostringstream s;
  s << "ground truth: " << groundtruth_path << " (" << groundtruth_poses << " poses)\n"
    << "estimate:     " << estimate_path << " (" << estimate_poses << " poses)\n"
    << "ATE: " << ate.matched << " poses matched within " << options.max_dt_s
    << " s, rigid alignment without scale\n"
    << "RPE: " << rpe.pairs << " pairs " << options.delta_s << " s apart\n";
  if (groundtruth_repeated + estimate_repeated > 0)
    s << "note: rows with a repeated timestamp (the last one kept, as the TUM tools do): "
      << estimate_repeated << " in the estimate, " << groundtruth_repeated
      << " in the ground truth\n";
  s << "\n";
  s << std::left << std::setw(22) << "" << std::right << std::setw(10) << "rmse" << std::setw(10)
    << "mean" << std::setw(10) << "median" << std::setw(10) << "max"
    << "\n";
  auto row = [&](const std::string& name, bool ok, const ErrorStats& e, int precision,
                 const std::string& why) {
    s << std::left << std::setw(22) << name << std::right;
    if (!ok) {
      s << "  n/a (" << why << ")\n";
      return;
    }
    s << std::fixed << std::setprecision(precision) << std::setw(10) << e.rmse << std::setw(10)
      << e.mean << std::setw(10) << e.median << std::setw(10) << e.max << "\n";
  };
  std::ostringstream d;
  d << options.delta_s;
  row("ATE (m)", ate.success, ate.error_m, 4, ate.reason);
  row("RPE trans (m/" + d.str() + "s)", rpe.success, rpe.trans_m, 4, rpe.reason);
  row("RPE rot (deg/" + d.str() + "s)", rpe.success, rpe.rot_deg, 3, rpe.reason);
  return s.str();
}

std::string EvaluationReport::Json() const {
  std::ostringstream s;
  s << std::setprecision(9) << "{\"groundtruth\": " << JsonString(groundtruth_path)
    << ", \"estimate\": " << JsonString(estimate_path)
    << ", \"groundtruth_poses\": " << groundtruth_poses
    << ", \"estimate_poses\": " << estimate_poses
    << ", \"groundtruth_repeated\": " << groundtruth_repeated
    << ", \"estimate_repeated\": " << estimate_repeated << ", \"max_dt_s\": " << options.max_dt_s
    << ", \"delta_s\": " << options.delta_s
    << ",\n \"ate\": {\"success\": " << (ate.success ? "true" : "false")
    << ", \"matched\": " << ate.matched << ", \"reason\": " << JsonString(ate.reason)
    << ", \"error_m\": " << JsonStats(ate.error_m, ate.success)
    << "},\n \"rpe\": {\"success\": " << (rpe.success ? "true" : "false")
    << ", \"pairs\": " << rpe.pairs << ", \"reason\": " << JsonString(rpe.reason)
    << ", \"trans_m\": " << JsonStats(rpe.trans_m, rpe.success)
    << ", \"rot_deg\": " << JsonStats(rpe.rot_deg, rpe.success) << "}}\n";
  return s.str();
}

}  // namespace rgbdvo
