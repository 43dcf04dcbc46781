#pragma once
// The fallback for frames that features cannot carry (motion blur, textureless walls): the
// motion between two depth images by point-to-plane ICP, seeded by a predicted motion. Depth is
// not blurred by fast turns the way colour is, and it needs no texture. It uses OpenCV contrib's
// ICPOdometry (Newcombe et al., KinectFusion, ISMAR 2011: projective association, coarse to
// fine) on the depth camera's pinhole model (K_ir; lens distortion ignored).

#include <opencv2/core.hpp>
#include <string>

#include "rgbdvo/calibration.hpp"
#include "rgbdvo/geometry.hpp"

namespace rgbdvo {

struct DepthAlignOptions {
  // Largest motion accepted between the two depth images (as the paper's verification).
  double max_translation_m = 0.5;
  double max_rotation_deg = 60.0;
  void Check() const;
};

struct DepthAlignResult {
  bool success = false;
  Rigid3d prev_from_cur = Rigid3d::Identity();  // p_prev = R * p_cur + t
  std::string reason;                           // why it failed ("" on success)
};

// prev_depth_m and cur_depth_m: CV_32FC1 metres in the depth camera, 0 = no reading, same size.
// Throws std::invalid_argument for other types or sizes.
DepthAlignResult AlignDepth(const DepthAlignOptions& options, const Calibration& calib,
                            const cv::Mat& prev_depth_m, const cv::Mat& cur_depth_m,
                            const Rigid3d& prev_from_cur_guess);

}  // namespace rgbdvo
