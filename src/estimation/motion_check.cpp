#include "rgbdvo/estimation/motion_check.hpp"

#include <sstream>
#include <stdexcept>

namespace rgbdvo {

void MotionCheckOptions::Check() const {
  if (min_inliers < 3) throw std::invalid_argument("MotionCheckOptions.min_inliers must be >= 3");
  if (!(max_translation_m > 0))
    throw std::invalid_argument("MotionCheckOptions.max_translation_m must be > 0");
  if (!(max_rotation_deg > 0))
    throw std::invalid_argument("MotionCheckOptions.max_rotation_deg must be > 0");
}

std::string CheckMotion(const MotionCheckOptions& o, const MotionEstimate& r) {
  std::ostringstream reason;
  if (!r.success)
    reason << "ransac_" << r.reason;
  else if (static_cast<int>(r.inliers.size()) < o.min_inliers)
    reason << "inliers<" << o.min_inliers;
  else if (r.prev_from_cur.translation().norm() > o.max_translation_m)
    reason << "translation>" << o.max_translation_m << "m";
  else if (RotationAngleDeg(r.prev_from_cur.linear()) > o.max_rotation_deg)
    reason << "rotation>" << o.max_rotation_deg << "deg";
  return reason.str();
}

}  // namespace rgbdvo
