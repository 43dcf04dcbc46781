#include "rgbdvo/estimation/refine.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "rgbdvo/estimation/planar_motion.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

constexpr double kFocalPx = 520;

// n pairs p_prev = prev_from_cur * p_cur observed with Gaussian noise: pixel_sigma (pixels, in x
// and y) and depth_sigma_m on the previous frame's point, p_cur exact; depths 1-3 m.
std::vector<PointPair> NoisyPairs(std::mt19937& rng, const Rigid3d& prev_from_cur, int n,
                                  double pixel_sigma, double depth_sigma_m) {
  std::uniform_real_distribution<double> xy(-0.5, 0.5), z(1.0, 3.0);
  std::normal_distribution<double> px(0, pixel_sigma), dz(0, depth_sigma_m);
  std::vector<PointPair> pairs;
  for (int i = 0; i < n; ++i) {
    const double depth = z(rng);
    PointPair p;
    const double v = xy(rng);  // one draw per statement, last first: the same on every compiler
    const double u = xy(rng);
    p.p_cur = Eigen::Vector3d(u * depth, v * depth, depth);
    const Eigen::Vector3d q = prev_from_cur * p.p_cur;
    const double zq = q.z() + dz(rng);
    const double ey = px(rng);
    const double ex = px(rng);
    p.p_prev = Eigen::Vector3d((q.x() / q.z() + ex / kFocalPx) * zq,
                               (q.y() / q.z() + ey / kFocalPx) * zq, zq);
    pairs.push_back(p);
  }
  return pairs;
}

std::vector<int> All(size_t n) {
  std::vector<int> idx(n);
  for (size_t i = 0; i < n; ++i) idx[i] = static_cast<int>(i);
  return idx;
}

}  // namespace

TEST_CASE("Noise at the model's sigmas gives a noise scale of 1") {
  std::mt19937 rng(3);
  const Rigid3d T = RandomRigid(rng, 0.05, 0.03);
  const RefineOptions o;
  // The depth noise at 2 m (the middle of the depths) is c * 4 m^2; one-sided noise on p_prev
  // only, so the symmetric residuals see it once.
  const auto pairs = NoisyPairs(rng, T, 400, o.pixel_sigma, o.depth_noise_coeff * 4.0);
  const NoiseScale s = EstimateNoiseScale(o, kFocalPx, pairs, All(pairs.size()), T);
  CHECK(s.pixel == Approx(1.0).margin(0.15));
  CHECK(s.depth == Approx(1.0).margin(0.3));
}

TEST_CASE("Blur-like pixel noise is measured in the pixel scale, not the depth scale") {
  std::mt19937 rng(4);
  const Rigid3d T = RandomRigid(rng, 0.1, 0.05);
  const RefineOptions o;
  const auto pairs = NoisyPairs(rng, T, 400, 4.0 * o.pixel_sigma, 1e-6);
  const NoiseScale s = EstimateNoiseScale(o, kFocalPx, pairs, All(pairs.size()), T);
  CHECK(s.pixel == Approx(4.0).epsilon(0.15));
  CHECK(s.depth == 1.0);
}

TEST_CASE("The noise scale ignores a minority of outliers and is 1 without pairs") {
  std::mt19937 rng(5);
  const Rigid3d T = RandomRigid(rng, 0.1, 0.05);
  const RefineOptions o;
  auto pairs = NoisyPairs(rng, T, 300, 3.0, 1e-6);
  for (int i = 0; i < 90; ++i) pairs[i].p_prev += Eigen::Vector3d(0.3, -0.2, 0.5);  // 30 %
  const NoiseScale s = EstimateNoiseScale(o, kFocalPx, pairs, All(pairs.size()), T);
  CHECK(s.pixel > 2.5);
  CHECK(s.pixel < 6.0);  // the median sits among the inliers (30 % outliers shift it upwards)
  const NoiseScale none = EstimateNoiseScale(o, kFocalPx, pairs, {}, T);
  CHECK(none.pixel == 1.0);
  CHECK(none.depth == 1.0);
}

TEST_CASE("Refinement with the measured scale recovers a motion under blur-like noise") {
  std::mt19937 rng(6);
  const Rigid3d T = RandomRigid(rng, 0.15, 0.05);
  const RefineOptions o;
  const auto pairs = NoisyPairs(rng, T, 200, 4.0, 1e-6);
  const std::vector<int> idx = All(pairs.size());
  Rigid3d start = T;
  start.translation() += Eigen::Vector3d(0.01, -0.01, 0.005);
  const RefineOptions scaled = ScaleNoise(o, EstimateNoiseScale(o, kFocalPx, pairs, idx, T));
  CHECK(scaled.pixel_sigma > 3.0 * o.pixel_sigma);
  const RefineResult r = RefineMotion(scaled, kFocalPx, pairs, idx, start);
  CHECK(r.final_cost <= r.initial_cost);
  CHECK(RigidNear(r.prev_from_cur, T, 0.2, 0.005));
  // Every pair is an inlier at the measured scale; at the model's 1 px a third are cut away.
  int in_scaled = 0, in_model = 0;
  for (const PointPair& p : pairs) {
    in_scaled += WhitenedError(scaled, kFocalPx, p, r.prev_from_cur) < o.inlier_sigmas;
    in_model += WhitenedError(o, kFocalPx, p, r.prev_from_cur) < o.inlier_sigmas;
  }
  CHECK(in_scaled > 0.97 * pairs.size());
  CHECK(in_model < 0.8 * pairs.size());
}

TEST_CASE("The refinement's gradient matches central differences of its cost") {
  std::mt19937 rng(3);
  Rigid3d truth = Rigid3d::Identity();
  truth.linear() = AxisAngle({0.3, 1, -0.2}, 0.08);
  truth.translation() = Eigen::Vector3d(0.05, -0.02, 0.04);
  // Noise of several sigmas, so that part of the residuals lie beyond the Huber threshold and
  // both branches of the robust cost are checked; evaluated away from the minimum.
  const std::vector<PointPair> pairs = NoisyPairs(rng, truth, 60, 3.0, 0.02);
  Rigid3d at = truth;
  at.linear() = AxisAngle({1, 0, 0}, 0.01) * at.linear();
  at.translation() += Eigen::Vector3d(0.004, 0.002, -0.003);
  const RefineOptions options;
  Eigen::Matrix<double, 6, 1> gradient;
  RefineCost(options, kFocalPx, pairs, All(pairs.size()), at, nullptr, &gradient);
  constexpr double kH = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d(k) = kH;
    const auto moved = [&](double sign) {
      Rigid3d E = Rigid3d::Identity();
      const Eigen::Vector3d w = sign * d.head<3>();
      if (w.norm() > 0) E.linear() = AxisAngle(w, w.norm());
      E.translation() = sign * d.tail<3>();
      return E * at;
    };
    const double numeric =
        (RefineCost(options, kFocalPx, pairs, All(pairs.size()), moved(+1), nullptr, nullptr) -
         RefineCost(options, kFocalPx, pairs, All(pairs.size()), moved(-1), nullptr, nullptr)) /
        (2 * kH);
    INFO("component " << k << ": analytic " << gradient(k) << ", numeric " << numeric);
    CHECK(gradient(k) == Approx(numeric).epsilon(1e-4).margin(1e-6 * gradient.norm()));
  }
  CHECK(gradient.norm() > 1.0);  // away from the minimum: the check is not of zeros
}

TEST_CASE("The planar refinement stays planar and beats the 6-DOF one on planar motion") {
  // A camera pitched 15 degrees down and rolled 4 degrees, driven on a floor: 30 pairs at 2 px
  // and 1 cm of depth noise, started 1 cm and 0.5 degrees off, over 50 motions.
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> yaw(-0.1, 0.1), step(-0.05, 0.05);
  const Eigen::Matrix3d L = (Eigen::AngleAxisd(0.07, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(-0.26, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  RefineOptions planar;
  planar.planar_level_from_cam = L;
  double err3 = 0, err6 = 0;
  for (int i = 0; i < 50; ++i) {
    const double y = yaw(rng), x = step(rng), z = step(rng);
    const Rigid3d truth = PlanarMotion(L, y, x, z);
    const auto pairs = NoisyPairs(rng, truth, 30, 2.0, 0.01);
    const Rigid3d start = PlanarMotion(L, y + 0.009, x + 0.01, z - 0.01);
    const Rigid3d r3 = RefineMotion(planar, kFocalPx, pairs, All(30), start).prev_from_cur;
    const Rigid3d r6 = RefineMotion(RefineOptions{}, kFocalPx, pairs, All(30), start).prev_from_cur;
    // Still a planar motion: the height kept, the floor's normal kept.
    const Eigen::Vector3d normal = L.transpose() * Eigen::Vector3d::UnitY();
    REQUIRE(std::abs(normal.dot(r3.translation())) < 1e-9);
    REQUIRE((r3.linear() * normal - normal).norm() < 1e-9);
    err3 +=
        std::pow(TranslationError(r3, truth), 2) + std::pow(RotationErrorDeg(r3, truth) / 50, 2);
    err6 +=
        std::pow(TranslationError(r6, truth), 2) + std::pow(RotationErrorDeg(r6, truth) / 50, 2);
  }
  INFO("RMS error (m, with 1 degree as 2 cm): planar " << std::sqrt(err3 / 50) << ", 6-DOF "
                                                       << std::sqrt(err6 / 50));
  CHECK(err3 < 0.5 * err6);
}

TEST_CASE("Inlier selection repeated to its fixed point no longer depends on the start") {
  // 200 pairs at the model's noise and 40 outliers, selected from two starts a few millimetres
  // and a fraction of a degree off (as two RANSAC hypotheses): one round keeps different
  // inliers from each, the rounds to the fixed point the same ones and the same motion.
  std::mt19937 rng(41);
  const Rigid3d T = RandomRigid(rng, 0.1, 0.05);
  const RefineOptions o;
  REQUIRE(o.selection_rounds > 1);
  auto pairs = NoisyPairs(rng, T, 240, o.pixel_sigma, o.depth_noise_coeff * 4.0);
  std::uniform_real_distribution<double> offset(0.05, 0.3);
  for (int i = 200; i < 240; ++i) {
    Eigen::Vector3d shift = RandomVector(rng, offset);
    shift.y() = -shift.y();
    pairs[i].p_prev += shift;
  }
  Rigid3d a = T, b = T;
  a.translation() += Eigen::Vector3d(0.004, 0, 0);
  b.linear() = Eigen::AngleAxisd(-0.005, Eigen::Vector3d::UnitY()) * b.linear();
  RefineOptions once = o;
  once.selection_rounds = 1;

  const SelectionRefinement a1 = RefineWithInlierSelection(once, kFocalPx, pairs, a);
  const SelectionRefinement b1 = RefineWithInlierSelection(once, kFocalPx, pairs, b);
  REQUIRE(a1.refine);
  REQUIRE(b1.refine);
  CHECK(a1.rounds == 1);
  CHECK(a1.inliers != b1.inliers);

  const SelectionRefinement ra = RefineWithInlierSelection(o, kFocalPx, pairs, a);
  const SelectionRefinement rb = RefineWithInlierSelection(o, kFocalPx, pairs, b);
  REQUIRE(ra.refine);
  REQUIRE(rb.refine);
  CHECK(ra.rounds > 1);
  CHECK(ra.inliers == rb.inliers);
  // The same motion up to the refinement's own convergence; one round's two motions are not.
  INFO("one round: " << RotationErrorDeg(a1.refine->prev_from_cur, b1.refine->prev_from_cur)
                     << " deg, "
                     << TranslationError(a1.refine->prev_from_cur, b1.refine->prev_from_cur)
                     << " m apart; to the fixed point: "
                     << RotationErrorDeg(ra.refine->prev_from_cur, rb.refine->prev_from_cur)
                     << " deg, "
                     << TranslationError(ra.refine->prev_from_cur, rb.refine->prev_from_cur)
                     << " m");
  CHECK(RigidNear(ra.refine->prev_from_cur, rb.refine->prev_from_cur, 1e-3, 1e-5));
  CHECK_FALSE(RigidNear(a1.refine->prev_from_cur, b1.refine->prev_from_cur, 1e-3, 1e-5));
  CHECK(RigidNear(ra.refine->prev_from_cur, T, 0.05, 0.002));
  CHECK(ra.inliers.size() > 190);
  CHECK(ra.inliers.back() < 200);  // no outlier: they are the last 40
  CHECK(ra.inliers.size() > a1.inliers.size());

  // The fixed point: selecting again from its motion keeps the same pairs in one round.
  const SelectionRefinement again =
      RefineWithInlierSelection(o, kFocalPx, pairs, ra.refine->prev_from_cur);
  CHECK(again.rounds == 1);
  CHECK(again.inliers == ra.inliers);
}

TEST_CASE("Inlier selection with fewer than 3 pairs refines nothing") {
  std::mt19937 rng(42);
  const Rigid3d T = RandomRigid(rng, 0.1, 0.05);
  const auto pairs = NoisyPairs(rng, T, 2, 1.0, 0.001);
  const SelectionRefinement r = RefineWithInlierSelection(RefineOptions{}, kFocalPx, pairs, T);
  CHECK_FALSE(r.refine);
  CHECK(r.inliers.empty());
  CHECK(r.rounds == 0);
  RefineOptions bad;
  bad.selection_rounds = 0;
  CHECK_THROWS_AS(bad.Check(), std::invalid_argument);
}

namespace {

// The points of a layout seen by both cameras, each observation with Gaussian noise at the
// model's sigmas (pixel_sigma in x and y, depth_noise_coeff * z^2 in depth).
std::vector<PointPair> ObservedPairs(std::mt19937& rng, const RefineOptions& o,
                                     const std::vector<Eigen::Vector3d>& points_cur,
                                     const Rigid3d& prev_from_cur) {
  std::normal_distribution<double> n01(0, 1);
  const auto observe = [&](const Eigen::Vector3d& p) {
    const double z = p.z() + n01(rng) * o.depth_noise_coeff * p.z() * p.z();
    const double ey = n01(rng);  // one draw per statement, last first: the same on every compiler
    const double ex = n01(rng);
    return Eigen::Vector3d((p.x() / p.z() + ex * o.pixel_sigma / kFocalPx) * z,
                           (p.y() / p.z() + ey * o.pixel_sigma / kFocalPx) * z, z);
  };
  std::vector<PointPair> pairs;
  for (const Eigen::Vector3d& p : points_cur) {
    PointPair pair;
    pair.p_cur = observe(p);
    pair.p_prev = observe(prev_from_cur * p);
    pairs.push_back(pair);
  }
  return pairs;
}

// Over many noisy observations of the layout, the standard deviation of the refined translation
// along its least certain direction (the largest eigenvalue of its sample covariance).
double EmpiricalTranslationStd(std::mt19937& rng, const RefineOptions& o,
                               const std::vector<Eigen::Vector3d>& points_cur,
                               const Rigid3d& truth) {
  constexpr int kTrials = 400;
  std::vector<Eigen::Vector3d> errors;
  for (int i = 0; i < kTrials; ++i) {
    const auto pairs = ObservedPairs(rng, o, points_cur, truth);
    const Rigid3d r = RefineMotion(o, kFocalPx, pairs, All(pairs.size()), truth).prev_from_cur;
    errors.push_back(r.translation() - truth.translation());
  }
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& e : errors) cov += e * e.transpose();
  cov /= kTrials;
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues()(2));
}

}  // namespace

TEST_CASE("TranslationStd predicts the spread of the refined translation") {
  // Two layouts at the model's noise: 40 points spread over 1-3 m, and 12 points crowded on a
  // wall 3 m ahead (a turn and a sideways slide look alike there). The predicted standard
  // deviation along the least certain direction matches the one measured over 400 noisy
  // observations of each, and tells the two apart.
  std::mt19937 rng(41);
  const RefineOptions o;
  const Rigid3d truth = RandomRigid(rng, 0.05, 0.03);
  std::uniform_real_distribution<double> u(-0.5, 0.5), depth(1.0, 3.0);
  std::vector<Eigen::Vector3d> spread, wall;
  for (int i = 0; i < 40; ++i) {
    const double z = depth(rng);
    const double y = u(rng);  // one draw per statement, last first: the same on every compiler
    const double x = u(rng);
    spread.emplace_back(x * z, y * z, z);
  }
  for (int i = 0; i < 12; ++i) {
    const double y = u(rng);
    const double x = u(rng);
    wall.emplace_back(x * 0.6, y * 0.6, 3.0);
  }
  for (const auto* points : {&spread, &wall}) {
    std::vector<PointPair> exact;
    for (const Eigen::Vector3d& p : *points) exact.push_back({truth * p, p});
    const double predicted = TranslationStd(o, kFocalPx, exact, All(exact.size()), truth);
    const double measured = EmpiricalTranslationStd(rng, o, *points, truth);
    INFO((points == &spread ? "spread" : "wall")
         << ": predicted " << predicted * 1000 << " mm, measured " << measured * 1000 << " mm");
    CHECK(predicted == Approx(measured).epsilon(0.2));
  }
  std::vector<PointPair> exact_spread, exact_wall;
  for (const Eigen::Vector3d& p : spread) exact_spread.push_back({truth * p, p});
  for (const Eigen::Vector3d& p : wall) exact_wall.push_back({truth * p, p});
  CHECK(TranslationStd(o, kFocalPx, exact_wall, All(12), truth) >
        5 * TranslationStd(o, kFocalPx, exact_spread, All(40), truth));
}

TEST_CASE("TranslationStd is infinite where the pairs leave the translation free") {
  // Two pairs cannot fix a rigid motion.
  const RefineOptions o;
  const std::vector<PointPair> two = {{Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, 2)},
                                      {Eigen::Vector3d(0.5, 0, 2), Eigen::Vector3d(0.5, 0, 2)}};
  CHECK(std::isinf(TranslationStd(o, kFocalPx, two, All(2), Rigid3d::Identity())));
}
