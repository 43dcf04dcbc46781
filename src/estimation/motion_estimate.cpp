#include "rgbdvo/estimation/motion_estimate.hpp"

#include <utility>

namespace rgbdvo {

MotionEstimate MotionEstimate::FromRansac(RansacResult ransac) {
  MotionEstimate e;
  e.success = ransac.success;
  e.prev_from_cur = ransac.prev_from_cur;
  e.inliers = ransac.inliers;
  e.reason = ransac.reason;
  e.ransac = std::move(ransac);
  return e;
}

}  // namespace rgbdvo
