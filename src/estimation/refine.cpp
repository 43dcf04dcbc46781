#include "rgbdvo/estimation/refine.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rgbdvo {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// d(residual)/d(point) of Residual: [a 0 b; 0 a c; 0 0 d].
struct ResidualJacobian {
  double a, b, c, d;
};

// Whitened residual of point q (in the observing camera) against observation obs (a point
// whose X/Z, Y/Z, Z are what that camera measured), and d(residual)/d(q).
inline Eigen::Vector3d Residual(const RefineOptions& o, double f, const Eigen::Vector3d& q,
                                const Eigen::Vector3d& obs, ResidualJacobian* J) {
  const double su = o.pixel_sigma / f;  // pixel noise in normalised coordinates
  const double sz = o.depth_noise_coeff * obs.z() * obs.z();
  const double iz = 1.0 / q.z();
  Eigen::Vector3d r((q.x() * iz - obs.x() / obs.z()) / su, (q.y() * iz - obs.y() / obs.z()) / su,
                    (q.z() - obs.z()) / sz);
  if (J) *J = {iz / su, -q.x() * iz * iz / su, -q.y() * iz * iz / su, 1 / sz};
  return r;
}

// H += w J^T J (its upper triangle only: Evaluate mirrors it once at the end) and g += w J^T r,
// for the Rows x 6 Jacobian J given row by row. Plain arrays and loops: Eigen's fixed-size
// products here went through the stack, written in halves and read back whole, and took a
// third more time per refinement.
template <int Rows>
void AddWeighted(const double (&J)[Rows][6], const double (&r)[Rows], double w, Mat6* H, Vec6* g) {
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i <= j; ++i) {
      double sum = 0;
      for (int k = 0; k < Rows; ++k) sum += w * J[k][i] * J[k][j];
      (*H)(i, j) += sum;
    }
    double sum = 0;
    for (int k = 0; k < Rows; ++k) sum += w * J[k][j] * r[k];
    (*g)(j) += sum;
  }
}

// The normal equations of one side of the pairs, by 3 x 3 blocks: a residual r = D(point) with
// d(point)/d(delta) = [Hat(x) | -I] (x the point, delta = (omega, v)) adds, with M = w D^T D and
// m = w D^T r, Hat(x)^T M Hat(x) = -Hat(x) M Hat(x) to the rotation block (rr, upper triangle),
// Hat(x) M to the rotation-translation block (rt), M to the translation block (tt, upper) and
// (x cross -m, -m) to the gradient. A residual with d(point)/d(delta) = [-Hat(x) | I] adds the
// same with -m for m. Summing the 3 x 3 information of each point instead of the rows of its
// 3 x 6 Jacobian takes about a third of the arithmetic.
struct SideSums {
  double rr[3][3] = {}, rt[3][3] = {}, tt[3][3] = {};
  double gr[3] = {}, gt[3] = {};

  // D = [a 0 b; 0 a c; 0 0 d] (ResidualJacobian), m_sign = +1 for [Hat(x) | -I], -1 for
  // [-Hat(x) | I].
  void Add(const Eigen::Vector3d& x, const ResidualJacobian& D, const Eigen::Vector3d& r, double w,
           double m_sign) {
    const auto [a, b, c, d] = D;
    // M = w D^T D, symmetric.
    const double M[3][3] = {{w * a * a, 0, w * a * b},
                            {0, w * a * a, w * a * c},
                            {w * a * b, w * a * c, w * (b * b + c * c + d * d)}};
    const double m[3] = {m_sign * w * a * r.x(), m_sign * w * a * r.y(),
                         m_sign * w * (b * r.x() + c * r.y() + d * r.z())};
    const double hat[3][3] = {{0, -x.z(), x.y()}, {x.z(), 0, -x.x()}, {-x.y(), x.x(), 0}};
    double A[3][3];  // Hat(x) M
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        A[i][j] = hat[i][0] * M[0][j] + hat[i][1] * M[1][j] + hat[i][2] * M[2][j];
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) {
        rr[i][j] -= A[i][0] * hat[0][j] + A[i][1] * hat[1][j] + A[i][2] * hat[2][j];
        tt[i][j] += M[i][j];
      }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rt[i][j] += A[i][j];
    // x cross -m = -(Hat(x) m).
    for (int i = 0; i < 3; ++i) {
      gr[i] -= hat[i][0] * m[0] + hat[i][1] * m[1] + hat[i][2] * m[2];
      gt[i] -= m[i];
    }
  }

  // H += blocks rotated by R (R X R^T; the gradient R g), into H's upper triangle.
  void AddTo(const Eigen::Matrix3d& R, Mat6* H, Vec6* g) const {
    const auto full = [](const double(&x)[3][3], bool symmetric) {
      Eigen::Matrix3d m;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m(i, j) = symmetric && j < i ? x[j][i] : x[i][j];
      return m;
    };
    const Eigen::Matrix3d Hrr = R * full(rr, true) * R.transpose();
    const Eigen::Matrix3d Hrt = R * full(rt, false) * R.transpose();
    const Eigen::Matrix3d Htt = R * full(tt, true) * R.transpose();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (j >= i) (*H)(i, j) += Hrr(i, j), (*H)(3 + i, 3 + j) += Htt(i, j);
        (*H)(i, 3 + j) += Hrt(i, j);
      }
    }
    g->head<3>() += R * Eigen::Vector3d(gr[0], gr[1], gr[2]);
    g->tail<3>() += R * Eigen::Vector3d(gt[0], gt[1], gt[2]);
  }
};

double Huber(double e, double k) { return e <= k ? 0.5 * e * e : k * (e - 0.5 * k); }

// Robust cost and, if H/g are given, the Gauss-Newton system for a left perturbation
// prev_from_cur <- Exp(delta) * prev_from_cur, delta = (omega, v).
double Evaluate(const RefineOptions& o, double f, const std::vector<PointPair>& pairs,
                const std::vector<int>& idx, const DepthPlaneTerm* dense, const Rigid3d& T, Mat6* H,
                Vec6* g) {
  double cost = 0;
  if (H) H->setZero(), g->setZero();
  if (dense) {
    // Truncated Huber: a point beyond inlier_sigmas (an occlusion, a moved object) or on no
    // reading costs as much as one at the cut and pulls nothing.
    const double k = o.huber_sigmas, cut = o.inlier_sigmas, cut_cost = Huber(cut, k);
    Eigen::Matrix<double, 1, 6> J;
    for (size_t i = 0; i < dense->size(); ++i) {
      double r;
      if (!dense->Residual(i, T, &r, H ? &J : nullptr) || std::abs(r) > cut) {
        cost += cut_cost;
        continue;
      }
      const double e = std::abs(r);
      cost += Huber(e, k);
      if (!H) continue;
      const double rows[1][6] = {{J(0), J(1), J(2), J(3), J(4), J(5)}}, res[1] = {r};
      AddWeighted(rows, res, e <= k ? 1.0 : k / e, H, g);
    }
  }
  // The pairs' residuals both ways: the cur point seen from prev (q; d(q)/d(delta) = [-Hat(q) |
  // I] for Exp(delta) q ~ q + omega x q + v) and the prev point seen from cur (s; T^-1 Exp(-delta)
  // p ~ s + R^T(p x omega - v), d(s)/d(delta) = R^T [Hat(p) | -I] = [Hat(R^T p) | -I] (R^T, R^T):
  // summed with x = R^T p and rotated by R once at the end).
  const Eigen::Matrix3d R = T.linear(), Rt = R.transpose();
  const Eigen::Vector3d Rt_t = Rt * T.translation();
  SideSums in_prev, in_cur;
  for (int k : idx) {
    const PointPair& p = pairs[k];
    const Eigen::Vector3d q = T * p.p_cur;                        // cur point in prev
    const Eigen::Vector3d s = Rt * (p.p_prev - T.translation());  // prev point in cur
    if (q.z() <= 1e-6 || s.z() <= 1e-6) continue;
    ResidualJacobian Jq, Js;
    const Eigen::Vector3d rq = Residual(o, f, q, p.p_prev, H ? &Jq : nullptr);
    const Eigen::Vector3d rs = Residual(o, f, s, p.p_cur, H ? &Js : nullptr);
    const double eq = rq.norm(), es = rs.norm();
    cost += Huber(eq, o.huber_sigmas);
    cost += Huber(es, o.huber_sigmas);
    if (!H) continue;
    // IRLS weights.
    const double wq = eq <= o.huber_sigmas ? 1.0 : o.huber_sigmas / eq;
    const double ws = es <= o.huber_sigmas ? 1.0 : o.huber_sigmas / es;
    in_prev.Add(q, Jq, rq, wq, -1);
    in_cur.Add(s + Rt_t, Js, rs, ws, 1);  // R^T p
  }
  if (H) {
    in_prev.AddTo(Eigen::Matrix3d::Identity(), H, g);
    in_cur.AddTo(R, H, g);
    H->triangularView<Eigen::StrictlyLower>() = H->transpose();
  }
  const size_t n = idx.size() + (dense ? dense->size() : 0);
  return n == 0 ? 0 : cost / static_cast<double>(n);
}

// The planar model's left perturbations, in the camera frame: a turn about the level y axis
// and translations along the level x and z axes (delta = B * (yaw, x, z)).
Eigen::Matrix<double, 6, 3> PlanarBasis(const Eigen::Matrix3d& level_from_cam) {
  const Eigen::Matrix3d cam_from_level = level_from_cam.transpose();
  Eigen::Matrix<double, 6, 3> basis = Eigen::Matrix<double, 6, 3>::Zero();
  basis.block<3, 1>(0, 0) = cam_from_level.col(1);
  basis.block<3, 1>(3, 1) = cam_from_level.col(0);
  basis.block<3, 1>(3, 2) = cam_from_level.col(2);
  return basis;
}

Rigid3d Apply(const Vec6& d, const Rigid3d& T) {
  Rigid3d E = Rigid3d::Identity();
  const double angle = d.head<3>().norm();
  if (angle > 0) E.linear() = Eigen::AngleAxisd(angle, d.head<3>() / angle).toRotationMatrix();
  E.translation() = d.tail<3>();
  Rigid3d out = E * T;
  out.linear() = NearestRotation(out.linear());
  return out;
}

}  // namespace

void RefineOptions::Check() const {
  if (!(pixel_sigma > 0)) throw std::invalid_argument("RefineOptions.pixel_sigma must be > 0");
  if (!(depth_noise_coeff > 0))
    throw std::invalid_argument("RefineOptions.depth_noise_coeff must be > 0");
  if (!(huber_sigmas > 0)) throw std::invalid_argument("RefineOptions.huber_sigmas must be > 0");
  if (!(inlier_sigmas > 0)) throw std::invalid_argument("RefineOptions.inlier_sigmas must be > 0");
  if (max_iterations < 1) throw std::invalid_argument("RefineOptions.max_iterations must be >= 1");
  if (selection_rounds < 1)
    throw std::invalid_argument("RefineOptions.selection_rounds must be >= 1");
}

std::string RefineResult::Brief() const {
  std::ostringstream s;
  s << (success ? "refined" : "refinement failed") << " in " << iterations << " iterations, cost "
    << initial_cost << " -> " << final_cost;
  return s.str();
}

namespace {

// The whitened residuals of a pair in both directions (cur point seen from prev, prev point seen
// from cur); false when either point falls behind the other camera.
bool SymmetricResiduals(const RefineOptions& o, double f, const PointPair& p, const Rigid3d& T,
                        Eigen::Vector3d* in_prev, Eigen::Vector3d* in_cur) {
  const Eigen::Vector3d q = T * p.p_cur;
  const Eigen::Vector3d s = T.linear().transpose() * (p.p_prev - T.translation());
  if (q.z() <= 1e-6 || s.z() <= 1e-6) return false;
  *in_prev = Residual(o, f, q, p.p_prev, nullptr);
  *in_cur = Residual(o, f, s, p.p_cur, nullptr);
  return true;
}

}  // namespace

double WhitenedError(const RefineOptions& o, double f, const PointPair& p, const Rigid3d& T) {
  Eigen::Vector3d a, b;
  if (!SymmetricResiduals(o, f, p, T, &a, &b)) return std::numeric_limits<double>::infinity();
  return std::max(a.norm(), b.norm());
}

NoiseScale EstimateNoiseScale(const RefineOptions& o, double f, const std::vector<PointPair>& pairs,
                              const std::vector<int>& idx, const Rigid3d& T) {
  std::vector<double> pixel, depth;
  for (int k : idx) {
    Eigen::Vector3d a, b;
    if (!SymmetricResiduals(o, f, pairs[k], T, &a, &b)) continue;
    for (const Eigen::Vector3d* r : {&a, &b}) {
      pixel.push_back(r->head<2>().norm());
      depth.push_back(std::abs(r->z()));
    }
  }
  NoiseScale scale;
  if (pixel.empty()) return scale;
  const auto median = [](std::vector<double>& v) {
    auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
  };
  constexpr double kMedianChi2 = 1.177;  // sqrt of chi-squared(2)'s median 1.386
  constexpr double kMedianAbsNormal = 0.674;
  scale.pixel = std::max(1.0, median(pixel) / kMedianChi2);
  scale.depth = std::max(1.0, median(depth) / kMedianAbsNormal);
  return scale;
}

RefineOptions ScaleNoise(RefineOptions o, const NoiseScale& scale) {
  o.pixel_sigma *= scale.pixel;
  o.depth_noise_coeff *= scale.depth;
  return o;
}

double TranslationStd(const RefineOptions& o, double f, const std::vector<PointPair>& pairs,
                      const std::vector<int>& idx, const Rigid3d& T) {
  Mat6 H;
  Vec6 g;
  Evaluate(o, f, pairs, idx, nullptr, T, &H, &g);
  // Each residual sees the noise of both of a pair's observations (twice the model's variance),
  // and both directions see the same two: a quarter of the summed information is what the
  // observations hold.
  H /= 4;
  // The information of the parameters (rotation first, then translation) and the translation's
  // part once the rotation is solved for: the Schur complement, whose inverse is the
  // translation's covariance.
  Eigen::MatrixXd A = H;
  int rotations = 3;
  if (o.planar_level_from_cam) {
    const Eigen::Matrix<double, 6, 3> B = PlanarBasis(*o.planar_level_from_cam);
    A = B.transpose() * H * B;
    rotations = 1;
  }
  const int translations = static_cast<int>(A.rows()) - rotations;
  const Eigen::MatrixXd Arr = A.topLeftCorner(rotations, rotations);
  const Eigen::MatrixXd Art = A.topRightCorner(rotations, translations);
  const Eigen::MatrixXd S = A.bottomRightCorner(translations, translations) -
                            Art.transpose() * Arr.completeOrthogonalDecomposition().solve(Art);
  const double weakest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues()(0);
  if (!(weakest > 0)) return std::numeric_limits<double>::infinity();
  return 1 / std::sqrt(weakest);
}

double RefineCost(const RefineOptions& o, double f, const std::vector<PointPair>& pairs,
                  const std::vector<int>& idx, const Rigid3d& T, const DepthPlaneTerm* dense,
                  Vec6* gradient) {
  Mat6 H;
  Vec6 g;
  const double cost = Evaluate(o, f, pairs, idx, dense, T, gradient ? &H : nullptr, &g);
  if (gradient) {
    const size_t n = idx.size() + (dense ? dense->size() : 0);
    *gradient = n == 0 ? Vec6::Zero() : Vec6(g / static_cast<double>(n));
  }
  return cost;
}

RefineResult RefineMotion(const RefineOptions& o, double f, const std::vector<PointPair>& pairs,
                          const std::vector<int>& idx, const Rigid3d& initial,
                          const DepthPlaneTerm* dense) {
  RefineResult result;
  result.prev_from_cur = initial;
  if (idx.size() < 3) return result;
  Mat6 H;
  Vec6 g;
  double cost = Evaluate(o, f, pairs, idx, dense, initial, &H, &g);
  result.initial_cost = cost;
  std::optional<Eigen::Matrix<double, 6, 3>> basis;
  if (o.planar_level_from_cam) basis = PlanarBasis(*o.planar_level_from_cam);
  double lambda = 1e-4;
  for (int it = 0; it < o.max_iterations; ++it) {
    result.iterations = it + 1;
    Vec6 delta;
    if (basis) {
      Eigen::Matrix3d A = basis->transpose() * H * *basis;
      A.diagonal() *= 1 + lambda;
      delta = *basis * -A.ldlt().solve(basis->transpose() * g);
    } else {
      Mat6 A = H;
      A.diagonal() *= 1 + lambda;
      delta = -A.ldlt().solve(g);
    }
    if (!delta.allFinite()) break;
    const Rigid3d candidate = Apply(delta, result.prev_from_cur);
    Mat6 H2;
    Vec6 g2;
    const double new_cost = Evaluate(o, f, pairs, idx, dense, candidate, &H2, &g2);
    if (new_cost < cost) {
      const bool converged = cost - new_cost < 1e-9 * cost || delta.norm() < 1e-10;
      result.prev_from_cur = candidate;
      cost = new_cost;
      H = H2;
      g = g2;
      lambda = std::max(lambda / 10, 1e-9);
      if (converged) break;
    } else {
      lambda *= 10;
      if (lambda > 1e6) break;
    }
  }
  result.final_cost = cost;
  result.success = true;
  return result;
}

SelectionRefinement RefineWithInlierSelection(const RefineOptions& o, double f,
                                              const std::vector<PointPair>& pairs,
                                              const Rigid3d& start, const DepthPlaneTerm* dense) {
  SelectionRefinement out;
  Rigid3d T = start;
  for (int round = 0; round < o.selection_rounds; ++round) {
    std::vector<int> selected;
    for (size_t k = 0; k < pairs.size(); ++k)
      if (WhitenedError(o, f, pairs[k], T) < o.inlier_sigmas)
        selected.push_back(static_cast<int>(k));
    if (selected.size() < 3 || (out.refine && selected == out.inliers)) break;
    out.inliers = std::move(selected);
    out.refine = RefineMotion(o, f, pairs, out.inliers, T, dense);
    out.rounds = round + 1;
    T = out.refine->prev_from_cur;
  }
  return out;
}

}  // namespace rgbdvo
