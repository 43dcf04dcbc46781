#include "rgbdvo/synthetic/synthetic_kinect.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "rgbdvo/sensor/camera.hpp"

using namespace rgbdvo;

namespace {

// The IR pixel that truly sees the point seen at colour pixel (u, v) at depth z.
Eigen::Vector2d TrueIrPixel(const SyntheticKinectOptions& o, double u, double v, double z) {
  const Eigen::Vector3d p_color((u - o.color.cx) / o.color.fx * z,
                                (v - o.color.cy) / o.color.fy * z, z);
  const Eigen::Vector3d p_ir = p_color - o.ir_in_color;
  return {o.ir.fx * p_ir.x() / p_ir.z() + o.ir.cx, o.ir.fy * p_ir.y() / p_ir.z() + o.ir.cy};
}

}  // namespace

TEST_CASE("Synthetic Kinect calibration: eq. 1 is exact at the reference depth") {
  SyntheticKinectOptions o;
  o.ir_in_color = {0.025, -0.004, 0.0};
  const Calibration c = SyntheticKinectCalibration(o);
  CHECK(c.fx == o.ir.fx);
  CHECK(c.cy == o.ir.cy);
  for (double u : {0.0, 320.0, 639.0})
    for (double v : {0.0, 479.0}) {
      const Eigen::Vector2d mapped = ColorToIr(c, {u, v});
      CHECK((mapped - TrueIrPixel(o, u, v, o.reference_depth_m)).norm() < 1e-9);
      // Elsewhere off by fx_ir * |o| * |1/z - 1/z_ref| pixels (synthetic_kinect.hpp).
      for (double z : {0.8, 1.5, 4.0}) {
        const double predicted =
            o.ir.fx * o.ir_in_color.norm() * std::abs(1.0 / z - 1.0 / o.reference_depth_m);
        CHECK((mapped - TrueIrPixel(o, u, v, z)).norm() == Approx(predicted).epsilon(0.01));
      }
    }
}

TEST_CASE("Synthetic Kinect options are checked") {
  SyntheticKinectOptions o;
  o.ir_in_color.z() = 0.01;
  CHECK_THROWS_AS(SyntheticKinectCalibration(o), std::invalid_argument);
}
