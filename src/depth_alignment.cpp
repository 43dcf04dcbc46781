#include "rgbdvo/depth_alignment.hpp"

#include <cmath>
#include <limits>
#include <opencv2/core/eigen.hpp>
#include <opencv2/rgbd.hpp>
#include <stdexcept>

namespace rgbdvo {
namespace {

cv::Mat OdometryDepth(const cv::Mat& depth_m) {
  cv::Mat d = depth_m.clone();
  d.setTo(std::numeric_limits<float>::quiet_NaN(), depth_m <= 0);  // no reading: NaN for OpenCV
  return d;
}

}  // namespace

void DepthAlignOptions::Check() const {
  if (!(max_translation_m > 0))
    throw std::invalid_argument("depth alignment max_translation_m must be > 0");
  if (!(max_rotation_deg > 0 && max_rotation_deg <= 180))
    throw std::invalid_argument("depth alignment max_rotation_deg must be in (0, 180]");
}

DepthAlignResult AlignDepth(const DepthAlignOptions& options, const Calibration& calib,
                            const cv::Mat& prev_depth_m, const cv::Mat& cur_depth_m,
                            const Rigid3d& prev_from_cur_guess) {
  if (prev_depth_m.type() != CV_32FC1 || cur_depth_m.type() != CV_32FC1 ||
      prev_depth_m.size() != cur_depth_m.size() || prev_depth_m.empty())
    throw std::invalid_argument("AlignDepth needs two CV_32FC1 depth images of the same size");
  DepthAlignResult result;
  const cv::Mat K =
      (cv::Mat_<double>(3, 3) << calib.fx, 0, calib.cx, 0, calib.fy, calib.cy, 0, 0, 1);
  cv::Ptr<cv::rgbd::ICPOdometry> icp = cv::rgbd::ICPOdometry::create(K);
  icp->setMinDepth(calib.min_depth_m);
  icp->setMaxDepth(calib.max_depth_m);
  icp->setMaxTranslation(options.max_translation_m);
  icp->setMaxRotation(options.max_rotation_deg);
  // compute(src, dst) gives Rt with p_dst = Rt * p_src (opencv2/rgbd/depth.hpp): src = current,
  // dst = previous frame, so Rt = prev_from_cur; the guess is its initial value.
  const cv::Mat empty_image, empty_mask;
  cv::Mat guess, Rt;
  cv::eigen2cv(Eigen::Matrix4d(prev_from_cur_guess.matrix()), guess);
  const bool ok = icp->compute(empty_image, OdometryDepth(cur_depth_m), empty_mask, empty_image,
                               OdometryDepth(prev_depth_m), empty_mask, Rt, guess);
  if (!ok || Rt.empty()) {
    result.reason = "icp_failed";
    return result;
  }
  Eigen::Matrix4d M;
  cv::cv2eigen(Rt, M);
  result.prev_from_cur.matrix() = M;
  if (!result.prev_from_cur.matrix().allFinite()) {
    result.reason = "icp_not_finite";
    return result;
  }
  result.success = true;
  return result;
}

}  // namespace rgbdvo
