#include "rgbdvo/estimation/ransac.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/estimation/rigid_align.hpp"

namespace rgbdvo {
namespace {

std::vector<int> Inliers(const std::vector<PointPair>& pairs, const Rigid3d& prev_from_cur,
                         double max_dist) {
  std::vector<int> inliers;
  const double max_sq = max_dist * max_dist;
  for (size_t k = 0; k < pairs.size(); ++k)
    if ((pairs[k].p_prev - prev_from_cur * pairs[k].p_cur).squaredNorm() < max_sq)
      inliers.push_back(static_cast<int>(k));
  return inliers;
}

double Rms(const std::vector<PointPair>& pairs, const std::vector<int>& idx, const Rigid3d& T) {
  if (idx.empty()) return 0;
  double sum = 0;
  for (int k : idx) sum += (pairs[k].p_prev - T * pairs[k].p_cur).squaredNorm();
  return std::sqrt(sum / static_cast<double>(idx.size()));
}

}  // namespace

void RansacOptions::Check() const {
  if (max_trials < 1) throw std::invalid_argument("RansacOptions.max_trials must be >= 1");
  if (sample_size < 3) throw std::invalid_argument("RansacOptions.sample_size must be >= 3");
  if (!(inlier_distance_m > 0))
    throw std::invalid_argument("RansacOptions.inlier_distance_m must be > 0");
  if (!(confidence >= 0 && confidence < 1))
    throw std::invalid_argument("RansacOptions.confidence must be in [0, 1)");
}

std::string RansacResult::Brief() const {
  std::ostringstream s;
  s << (success ? "RANSAC ok" : "RANSAC failed") << ": " << inliers.size() << " inliers, " << trials
    << " trials, rms " << rms_m * 1000 << " mm";
  if (!success) s << " (" << reason << ")";
  return s.str();
}

RansacResult EstimateRansac(const RansacOptions& o, const std::vector<PointPair>& pairs,
                            const MotionModel& model, Rng& rng) {
  RansacResult result;
  const int n = static_cast<int>(pairs.size());
  const int sample_size = model.sample_size;
  if (n < sample_size) {
    result.reason = "pairs<" + std::to_string(sample_size);
    return result;
  }
  std::vector<int> sample(sample_size);
  std::vector<int> best;
  int needed = o.max_trials;
  for (int trial = 0; trial < needed; ++trial) {
    ++result.trials;
    // Distinct random indices (partial Fisher-Yates on a small set by rejection).
    for (int i = 0; i < sample_size; ++i) {
      int k;
      do {
        k = std::uniform_int_distribution<int>(0, n - 1)(rng);
      } while (std::find(sample.begin(), sample.begin() + i, k) != sample.begin() + i);
      sample[i] = k;
    }
    const std::optional<Rigid3d> hypothesis = model.fit(pairs, sample);
    if (!hypothesis) continue;
    std::vector<int> inliers = Inliers(pairs, *hypothesis, o.inlier_distance_m);
    if (inliers.size() > best.size()) {
      best = std::move(inliers);
      if (o.confidence > 0) {
        // Trials for P(some sample all inliers) >= confidence: log(1-p) / log(1-w^s).
        const double all_in = std::pow(static_cast<double>(best.size()) / n, sample_size);
        if (all_in >= 1.0) {
          needed = trial + 1;
        } else if (all_in > 0) {
          const double k = std::ceil(std::log(1 - o.confidence) / std::log(1 - all_in));
          needed = static_cast<int>(std::min<double>(o.max_trials, k));
        }
      }
    }
  }
  const size_t min_pairs = static_cast<size_t>(model.min_pairs);
  if (best.size() < min_pairs) {
    result.reason = "no_hypothesis";
    return result;
  }
  // Refinement (paper section 3): SVD on the inliers' centred points; then the inliers of the
  // refined motion, refined once more if that set changed.
  std::optional<Rigid3d> refined = model.fit(pairs, best);
  if (!refined) {
    result.reason = "degenerate_inliers";
    return result;
  }
  std::vector<int> inliers = Inliers(pairs, *refined, o.inlier_distance_m);
  if (inliers.size() >= min_pairs && inliers != best) {
    if (std::optional<Rigid3d> again = model.fit(pairs, inliers)) refined = again;
  } else {
    inliers = best;
  }
  result.success = true;
  result.prev_from_cur = *refined;
  result.inliers = std::move(inliers);
  result.rms_m = Rms(pairs, result.inliers, *refined);
  return result;
}

RansacResult EstimateRigidRansac(const RansacOptions& o, const std::vector<PointPair>& pairs,
                                 Rng& rng) {
  const MotionModel rigid{o.sample_size, 3,
                          [](const std::vector<PointPair>& p, const std::vector<int>& idx) {
                            return AlignRigid(p, idx);
                          }};
  return EstimateRansac(o, pairs, rigid, rng);
}

}  // namespace rgbdvo
