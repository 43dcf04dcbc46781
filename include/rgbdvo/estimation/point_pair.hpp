#pragma once
// One 3D correspondence between two frames: what the estimators (Kabsch, RANSAC, the
// refinement) work on. Made from matched keypoints by the odometry (odometry/point_pairs.hpp).

#include <Eigen/Core>

namespace rgbdvo {

struct PointPair {
  Eigen::Vector3d p_prev;  // point in the previous (reference) camera frame, metres
  Eigen::Vector3d p_cur;   // the same point in the current camera frame, metres
};

}  // namespace rgbdvo
