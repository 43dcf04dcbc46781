#include "rgbdvo/estimation/motion_check.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

namespace {

MotionEstimate Result(int inliers, double trans_m, double rot_deg) {
  MotionEstimate r;
  r.success = true;
  r.inliers.resize(inliers);
  r.prev_from_cur.linear() = AxisAngle({0, 1, 0}, rot_deg * M_PI / 180);
  r.prev_from_cur.translation() = Eigen::Vector3d(trans_m, 0, 0);
  return r;
}

}  // namespace

TEST_CASE("Motion check applies the paper's limits") {
  const MotionCheckOptions o;  // 15 inliers, 0.5 m, 60 degrees
  CHECK(CheckMotion(o, Result(15, 0.49, 59)) == "");
  CHECK(CheckMotion(o, Result(14, 0.1, 1)) == "inliers<15");
  CHECK(CheckMotion(o, Result(100, 0.51, 1)) == "translation>0.5m");
  CHECK(CheckMotion(o, Result(100, 0.1, 61)) == "rotation>60deg");
  MotionEstimate failed;
  failed.reason = "pairs<4";
  CHECK(CheckMotion(o, failed) == "ransac_pairs<4");
}
