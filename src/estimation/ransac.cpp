#include "rgbdvo/estimation/ransac.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/estimation/rigid_align.hpp"

namespace rgbdvo {
namespace {

// The pairs' coordinates column by column: a hypothesis' errors are computed and its inliers
// counted in passes without branches, which the compiler vectorises (every trial tests every
// pair; most hypotheses are not the best so far and need only the count).
struct PairColumns {
  explicit PairColumns(const std::vector<PointPair>& pairs) {
    for (std::vector<double>* c : {&px, &py, &pz, &cx, &cy, &cz}) c->reserve(pairs.size());
    for (const PointPair& p : pairs) {
      px.push_back(p.p_prev.x()), py.push_back(p.p_prev.y()), pz.push_back(p.p_prev.z());
      cx.push_back(p.p_cur.x()), cy.push_back(p.p_cur.y()), cz.push_back(p.p_cur.z());
    }
  }
  size_t size() const { return px.size(); }
  std::vector<double> px, py, pz, cx, cy, cz;
};

// |p_prev - prev_from_cur * p_cur|^2 of every pair, into sq (as Eigen computes it, term by
// term); returns how many are below max_sq.
int SquaredErrors(const PairColumns& c, const Rigid3d& prev_from_cur, double max_sq, double* sq) {
  const Eigen::Matrix3d& R = prev_from_cur.linear();
  const Eigen::Vector3d& t = prev_from_cur.translation();
  const double r00 = R(0, 0), r01 = R(0, 1), r02 = R(0, 2), r10 = R(1, 0), r11 = R(1, 1),
               r12 = R(1, 2), r20 = R(2, 0), r21 = R(2, 1), r22 = R(2, 2);
  const double tx = t.x(), ty = t.y(), tz = t.z();
  const double *px = c.px.data(), *py = c.py.data(), *pz = c.pz.data(), *cx = c.cx.data(),
               *cy = c.cy.data(), *cz = c.cz.data();
  const size_t n = c.size();
  double count = 0;  // whole numbers, exact: the loop vectorises with a double sum
  for (size_t k = 0; k < n; ++k) {
    const double dx = px[k] - (r00 * cx[k] + r01 * cy[k] + r02 * cz[k] + tx);
    const double dy = py[k] - (r10 * cx[k] + r11 * cy[k] + r12 * cz[k] + ty);
    const double dz = pz[k] - (r20 * cx[k] + r21 * cy[k] + r22 * cz[k] + tz);
    sq[k] = dx * dx + dy * dy + dz * dz;
    count += sq[k] < max_sq ? 1.0 : 0.0;
  }
  return static_cast<int>(count);
}

std::vector<int> IndicesBelow(const std::vector<double>& sq, double max_sq) {
  std::vector<int> idx;
  for (size_t k = 0; k < sq.size(); ++k)
    if (sq[k] < max_sq) idx.push_back(static_cast<int>(k));
  return idx;
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
  const PairColumns columns(pairs);
  const double max_sq = o.inlier_distance_m * o.inlier_distance_m;
  std::vector<double> sq(pairs.size());
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
    if (static_cast<size_t>(SquaredErrors(columns, *hypothesis, max_sq, sq.data())) > best.size()) {
      best = IndicesBelow(sq, max_sq);
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
  SquaredErrors(columns, *refined, max_sq, sq.data());
  std::vector<int> inliers = IndicesBelow(sq, max_sq);
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
