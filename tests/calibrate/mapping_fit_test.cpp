#include "rgbdvo/calibrate/mapping_fit.hpp"

#include <catch2/catch.hpp>
#include <random>

using namespace rgbdvo;

namespace {

// n pairs of u_ir = A u_vis + B, v_ir = C v_vis + D over a 640x480 colour image, Gaussian
// noise sigma_px on each IR coordinate (a click is good to about a pixel).
std::vector<PixelPair> Synthesize(std::mt19937& rng, int n, double A, double B, double C, double D,
                                  double sigma_px) {
  std::uniform_real_distribution<double> u(20, 620), v(20, 460);
  std::normal_distribution<double> noise(0, sigma_px);
  std::vector<PixelPair> pairs;
  for (int i = 0; i < n; ++i) {
    PixelPair p;
    p.u_vis = u(rng), p.v_vis = v(rng);
    p.u_ir = A * p.u_vis + B + noise(rng);
    p.v_ir = C * p.v_vis + D + noise(rng);
    pairs.push_back(p);
  }
  return pairs;
}

}  // namespace

TEST_CASE("FitMapping recovers A-D exactly from noiseless pairs") {
  std::mt19937 rng(1);
  const auto pairs = Synthesize(rng, 3, 0.913462, 27.69231, 0.92, 18.5, 0.0);
  const MappingFit fit = FitMapping({}, pairs);
  REQUIRE(fit.success);
  CHECK(fit.A == Approx(0.913462).epsilon(1e-9));
  CHECK(fit.B == Approx(27.69231).epsilon(1e-9));
  CHECK(fit.C == Approx(0.92).epsilon(1e-9));
  CHECK(fit.D == Approx(18.5).epsilon(1e-9));
  CHECK(fit.rms_px < 1e-9);
  CHECK(fit.num_inliers == 3);
}

TEST_CASE("FitMapping recovers A-D from 20 pairs with 1 px click noise") {
  // Tolerances: with 20 pairs spread over the image and sigma 1 px, the slope's standard error
  // is about 1 / (sqrt(20) * 170 px) = 0.0013 and the offset's about 0.6 px; 4 sigma below.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const auto pairs = Synthesize(rng, 20, 0.91, 27.7, 1.03, -12.0, 1.0);
    const MappingFit fit = FitMapping({}, pairs);
    REQUIRE(fit.success);
    CHECK(fit.A == Approx(0.91).margin(0.006));
    CHECK(fit.C == Approx(1.03).margin(0.008));
    // Offsets are checked where they matter, at the image centre: the mapped centre pixel.
    CHECK(fit.A * 320 + fit.B == Approx(0.91 * 320 + 27.7).margin(1.0));
    CHECK(fit.C * 240 + fit.D == Approx(1.03 * 240 - 12.0).margin(1.0));
    CHECK(fit.rms_px == Approx(std::sqrt(2.0)).margin(0.6));  // two axes of 1 px noise
    REQUIRE(fit.residual_px.size() == 20);
  }
}

TEST_CASE("FitMapping reports each pair's residual") {
  std::vector<PixelPair> pairs = {
      {0, 0, 10, 10}, {100, 0, 110, 10}, {0, 100, 10, 110}, {100, 100, 110, 110}};
  pairs[3].u_ir += 4;  // one pair off by 4 px in u
  const MappingFit fit = FitMapping({}, pairs);
  REQUIRE(fit.success);
  // At u_vis = 100 the fit passes through the mean of 110 and 114: both are 2 px off; the
  // pairs at u_vis = 0 fit exactly.
  const std::vector<double> expected = {0, 2, 0, 2};
  for (size_t i = 0; i < 4; ++i) CHECK(fit.residual_px[i] == Approx(expected[i]).margin(1e-9));
  CHECK(fit.rms_px == Approx(std::sqrt(2.0)).margin(1e-9));
  CHECK(fit.A == Approx(1.02).margin(1e-12));
}

TEST_CASE("Robust FitMapping flags a bad click and fits without it") {
  std::mt19937 rng(3);
  auto pairs = Synthesize(rng, 12, 0.9, 30, 0.9, 20, 0.5);
  pairs[5].u_ir += 25;  // a click on the wrong corner
  const MappingFit plain = FitMapping({}, pairs);
  REQUIRE(plain.success);
  CHECK(plain.rms_px > 5);
  MappingFitOptions robust;
  robust.robust = true;
  const MappingFit fit = FitMapping(robust, pairs);
  REQUIRE(fit.success);
  CHECK(fit.num_inliers == 11);
  CHECK(fit.outlier[5]);
  CHECK(fit.residual_px[5] > 20);
  CHECK(fit.rms_px < 1.5);
  CHECK(fit.A == Approx(0.9).margin(0.01));
  CHECK_THAT(fit.Brief(), Catch::Contains("1 outlier(s) set aside"));
}

TEST_CASE("FitMapping refuses fewer than 3 pairs") {
  const MappingFit fit = FitMapping({}, {{0, 0, 1, 1}, {100, 100, 91, 91}});
  CHECK_FALSE(fit.success);
  CHECK(fit.reason == "need at least 3 pairs, have 2");
  CHECK_THAT(fit.Brief(), Catch::StartsWith("fit failed: need at least 3 pairs"));
  CHECK_FALSE(FitMapping({}, {}).success);
}

TEST_CASE("FitMapping refuses degenerate pairs (all u or all v equal)") {
  const MappingFit same_u = FitMapping({}, {{50, 0, 60, 5}, {50, 100, 60, 95}, {50, 200, 60, 185}});
  CHECK_FALSE(same_u.success);
  CHECK_THAT(same_u.reason, Catch::Contains("u_vis spans 0 px"));
  const MappingFit same_v = FitMapping({}, {{0, 70, 5, 60}, {100, 70, 95, 60}, {300, 70, 280, 60}});
  CHECK_FALSE(same_v.success);
  CHECK_THAT(same_v.reason, Catch::Contains("v_vis spans 0 px"));
  // A spread below min_spread_px is as bad: the scale would be set by click noise.
  const MappingFit close = FitMapping({}, {{0, 0, 0, 0}, {3, 100, 3, 90}, {6, 200, 6, 180}});
  CHECK_FALSE(close.success);
  CHECK_THAT(close.reason, Catch::Contains("u_vis spans 6 px (need >= 10 px"));
}

TEST_CASE("FitMapping refuses IR points that do not move (A = 0)") {
  const MappingFit fit = FitMapping({}, {{0, 0, 50, 0}, {100, 100, 50, 100}, {200, 50, 50, 50}});
  CHECK_FALSE(fit.success);
  CHECK_THAT(fit.reason, Catch::Contains("A or C is zero"));
}

TEST_CASE("MappingFitOptions::Check names the bad field") {
  MappingFitOptions o;
  o.min_pairs = 2;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("min_pairs"));
  o = {};
  o.outlier_px = 0;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("outlier_px"));
}

TEST_CASE("FitMapping finds the disparity term when the pairs' depths span enough") {
  // The Kinect's geometry: u_ir = A u + B + s_u / z with s_u = -580 * 0.025, depths 0.8-4 m,
  // 0.3 px click noise. With a narrow depth span the term is not observable: eq. 1.
  const double A = 1.105, B = -33.0, C = 1.1, D = -24.0, s_u = -14.5, s_v = 0.6;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(20, 620), v(20, 460), z(0.8, 4.0), near(2.0, 2.2);
  std::normal_distribution<double> noise(0, 0.3);
  const auto make = [&](std::uniform_real_distribution<double>& depth) {
    std::vector<PixelPair> pairs;
    for (int i = 0; i < 30; ++i) {
      PixelPair p;
      p.u_vis = u(rng), p.v_vis = v(rng), p.z_ir_m = depth(rng);
      p.u_ir = A * p.u_vis + B + s_u / p.z_ir_m + noise(rng);
      p.v_ir = C * p.v_vis + D + s_v / p.z_ir_m + noise(rng);
      pairs.push_back(p);
    }
    return pairs;
  };
  const MappingFit fit = FitMapping({}, make(z));
  REQUIRE(fit.success);
  CHECK(fit.depth_aware);
  CHECK(fit.A == Approx(A).margin(0.002));
  CHECK(fit.B == Approx(B).margin(1.0));
  CHECK(fit.s_u == Approx(s_u).margin(0.8));
  CHECK(fit.s_v == Approx(s_v).margin(0.8));
  CHECK(fit.rms_px < 0.6);
  // Eq. 1 on the same pairs leaves the depth-dependent part in the residuals.
  MappingFitOptions eq1;
  eq1.fit_disparity = false;
  const MappingFit plain = FitMapping(eq1, make(z));
  REQUIRE(plain.success);
  CHECK_FALSE(plain.depth_aware);
  CHECK(plain.s_u == 0);
  CHECK(plain.rms_px > 2 * fit.rms_px);
  const MappingFit narrow = FitMapping({}, make(near));
  REQUIRE(narrow.success);
  CHECK_FALSE(narrow.depth_aware);
}
