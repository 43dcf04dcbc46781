#include "rgbdvo/estimation/depth_term.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "rgbdvo/estimation/refine.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sensor/calibration_catalog.hpp"
#include "rgbdvo/sensor/camera.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

constexpr double kNoiseCoeff = 1.425e-3;  // the refinement's default sigma_z = c z^2
constexpr double kMaxJumpRatio = 0.03;    // the lifting's default

// Two depth images of the synthetic room, the current camera moved by a few cm and degrees.
struct DepthPairFixture {
  PinholeCamera camera;
  Calibration calib = CalibFor(camera);
  SyntheticScene scene;
  Rigid3d prev_from_cur = Rigid3d::Identity();
  cv::Mat prev_depth, cur_depth, rays;
  DepthPairFixture() {
    prev_from_cur.linear() =
        Eigen::AngleAxisd(0.05, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
    prev_from_cur.translation() = Eigen::Vector3d(0.04, -0.01, 0.03);
    prev_depth = scene.RenderDepth(camera, Rigid3d::Identity());
    cur_depth = scene.RenderDepth(camera, prev_from_cur);
    rays = DepthRays(calib, prev_depth.size());
  }
};

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

TEST_CASE("Depth points of the true motion lie on the reference surface", "[depth_term]") {
  DepthPairFixture f;
  const std::vector<Eigen::Vector3d> points =
      SampleDepthPoints(f.rays, f.cur_depth, Rigid3d::Identity(), 16);
  REQUIRE(points.size() > 1000);
  const DepthPlaneTerm term(f.calib, f.rays, f.prev_depth, Rigid3d::Identity(), points, kNoiseCoeff,
                            kMaxJumpRatio);
  std::vector<double> at_truth, moved;
  Rigid3d off = f.prev_from_cur;
  // 10 cm along the view: several sigmas off the surfaces (sigma_z is 6 mm at 2 m).
  off.translation() += Eigen::Vector3d(0, 0, 0.10);
  for (size_t i = 0; i < term.size(); ++i) {
    double r;
    if (term.Residual(i, f.prev_from_cur, &r, nullptr)) at_truth.push_back(std::abs(r));
    if (term.Residual(i, off, &r, nullptr)) moved.push_back(std::abs(r));
  }
  REQUIRE(at_truth.size() > term.size() / 2);
  CHECK(Median(at_truth) < 0.2);  // exact rendering: only the nearest-pixel association errs
  CHECK(Median(moved) > 3.0);
  CHECK(EstimateDepthTermScale(term, f.prev_from_cur) == 1.0);
  CHECK(EstimateDepthTermScale(term, off) > 3.0);
}

TEST_CASE("The depth term's derivative matches a numerical one", "[depth_term]") {
  DepthPairFixture f;
  const std::vector<Eigen::Vector3d> points =
      SampleDepthPoints(f.rays, f.cur_depth, Rigid3d::Identity(), 32);
  const DepthPlaneTerm term(f.calib, f.rays, f.prev_depth, Rigid3d::Identity(), points, kNoiseCoeff,
                            kMaxJumpRatio);
  constexpr double kEps = 1e-7;  // small enough that no point changes its reference pixel
  int compared = 0, agreeing = 0;
  for (size_t i = 0; i < term.size(); ++i) {
    double r;
    Eigen::Matrix<double, 1, 6> J;
    if (!term.Residual(i, f.prev_from_cur, &r, &J)) continue;
    Eigen::Matrix<double, 1, 6> numeric;
    bool ok = true;
    for (int k = 0; k < 6 && ok; ++k) {
      Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
      d(k) = kEps;
      Rigid3d E = Rigid3d::Identity();
      E.linear() =
          Eigen::AngleAxisd(d.head<3>().norm() > 0 ? d.head<3>().norm() : 0,
                            d.head<3>().norm() > 0 ? Eigen::Vector3d(d.head<3>().normalized())
                                                   : Eigen::Vector3d::UnitX())
              .toRotationMatrix();
      E.translation() = d.tail<3>();
      double r2;
      ok = term.Residual(i, E * f.prev_from_cur, &r2, nullptr);
      numeric(k) = (r2 - r) / kEps;
    }
    if (!ok) continue;
    ++compared;
    if ((numeric - J).norm() <= 1e-3 * std::max(1.0, J.norm())) ++agreeing;
  }
  REQUIRE(compared > 100);
  CHECK(agreeing >= 0.95 * compared);
}

TEST_CASE("Refinement with the depth term pins a motion that few noisy feature pairs leave loose",
          "[depth_term]") {
  DepthPairFixture f;
  std::mt19937 rng(11);
  // Six feature pairs with 2 px and 1 cm of noise on the previous frame's observation.
  std::normal_distribution<double> px(0, 2.0), dz(0, 0.01);
  std::uniform_real_distribution<double> xy(-0.4, 0.4), z(1.5, 3.0);
  std::vector<PointPair> pairs;
  for (int i = 0; i < 6; ++i) {
    const double depth = z(rng);
    PointPair p;
    const double v = xy(rng);  // one draw per statement, last first: the same on every compiler
    const double u = xy(rng);
    p.p_cur = Eigen::Vector3d(u * depth, v * depth, depth);
    const Eigen::Vector3d q = f.prev_from_cur * p.p_cur;
    const double zq = q.z() + dz(rng);
    const double ey = px(rng);
    const double ex = px(rng);
    p.p_prev = Eigen::Vector3d((q.x() / q.z() + ex / f.calib.fx) * zq,
                               (q.y() / q.z() + ey / f.calib.fx) * zq, zq);
    pairs.push_back(p);
  }
  const std::vector<int> all = {0, 1, 2, 3, 4, 5};
  const std::vector<Eigen::Vector3d> points =
      SampleDepthPoints(f.rays, f.cur_depth, Rigid3d::Identity(), 16);
  const DepthPlaneTerm term(f.calib, f.rays, f.prev_depth, Rigid3d::Identity(), points, kNoiseCoeff,
                            kMaxJumpRatio);
  RefineOptions options;
  const Rigid3d features_only =
      RefineMotion(options, f.calib.fx, pairs, all, Rigid3d::Identity()).prev_from_cur;
  const Rigid3d with_depth =
      RefineMotion(options, f.calib.fx, pairs, all, features_only, &term).prev_from_cur;
  INFO("features only: " << TranslationError(features_only, f.prev_from_cur) * 1000 << " mm "
                         << RotationErrorDeg(features_only, f.prev_from_cur) << " deg");
  INFO("with depth: " << TranslationError(with_depth, f.prev_from_cur) * 1000 << " mm "
                      << RotationErrorDeg(with_depth, f.prev_from_cur) << " deg");
  CHECK(TranslationError(with_depth, f.prev_from_cur) <
        0.35 * TranslationError(features_only, f.prev_from_cur));
  CHECK(RotationErrorDeg(with_depth, f.prev_from_cur) <
        0.35 * RotationErrorDeg(features_only, f.prev_from_cur));
}

TEST_CASE("DepthRays holds each pixel's undistorted ray, as NormalizeIr gives it", "[depth_term]") {
  // TUM fr1 (Sturm et al. 2012): strong radial distortion in the corners.
  const Calibration c = LoadCalibration(FindCalibration("tum_fr1"));
  const cv::Mat rays = DepthRays(c, {640, 480});
  double worst = 0, distortion = 0;
  for (int v = 0; v < rays.rows; ++v)
    for (int u = 0; u < rays.cols; ++u) {
      const Eigen::Vector2d x = NormalizeIr(c, {u, v});
      const cv::Vec2d& r = rays.at<cv::Vec2d>(v, u);
      worst = std::max({worst, std::abs(r[0] - x.x()), std::abs(r[1] - x.y())});
      distortion = std::max(distortion, std::abs(r[0] - (u - c.cx) / c.fx));
    }
  CHECK(worst < 1e-14);       // the same root (a billionth of a pixel is 2e-12 here)
  CHECK(distortion > 0.005);  // and the table is not the pinhole's (3 px off in the corners)
}
