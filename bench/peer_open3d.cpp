// rgbdvo_peer_open3d: Open3D 0.16 RGB-D odometry (pipelines::odometry::ComputeRGBDOdometry),
// frame to frame, default OdometryOption. Benchmark only.
#include <open3d/Open3DConfig.h>
#include <open3d/camera/PinholeCameraIntrinsic.h>
#include <open3d/geometry/Image.h>
#include <open3d/geometry/RGBDImage.h>
#include <open3d/pipelines/odometry/Odometry.h>
#include <open3d/utility/Logging.h>

#include <cstring>

#include "peer_runner.hpp"

namespace rgbdvo::bench {
namespace {

namespace o3d = open3d;

class Open3dPeer : public PeerOdometry {
 public:
  Open3dPeer(const std::string& method, const Calibration& calib) : method_(method) {
    if (method == "hybrid") {
      jacobian_ = std::make_unique<o3d::pipelines::odometry::RGBDOdometryJacobianFromHybridTerm>();
    } else if (method == "color") {
      jacobian_ = std::make_unique<o3d::pipelines::odometry::RGBDOdometryJacobianFromColorTerm>();
    } else {
      throw std::runtime_error("Open3D has no odometry " + method);
    }
    calib_ = calib;
    o3d::utility::SetVerbosityLevel(o3d::utility::VerbosityLevel::Error);
  }

  // ComputeRGBDOdometry(source, target) returns the transform that maps source points into the
  // target frame (Odometry.cpp: ComputeCorrespondence projects K*(R*p_s + t) into the target),
  // so with source = current and target = previous frame it is prev_from_cur.
  bool Track(const Frame& cur, Rigid3d* prev_from_cur) override {
    const int w = cur.bgr.cols, h = cur.bgr.rows;
    if (!intrinsic_) {
      intrinsic_ = std::make_unique<o3d::camera::PinholeCameraIntrinsic>(w, h, calib_.fx, calib_.fy,
                                                                         calib_.cx, calib_.cy);
    }
    o3d::geometry::Image color, depth;
    color.Prepare(w, h, 3, 1);
    for (int v = 0; v < h; ++v) {
      const cv::Vec3b* row = cur.bgr.ptr<cv::Vec3b>(v);
      for (int u = 0; u < w; ++u) {
        uint8_t* rgb = color.PointerAt<uint8_t>(u, v, 0);
        rgb[0] = row[u][2];
        rgb[1] = row[u][1];
        rgb[2] = row[u][0];
      }
    }
    depth.Prepare(w, h, 1, 4);
    for (int v = 0; v < h; ++v) {
      std::memcpy(depth.PointerAt<float>(0, v), cur.depth_m.ptr<float>(v), sizeof(float) * w);
    }
    // Depth already in metres (scale 1); truncated at the option's max depth, as Open3D's
    // CreateFromTUMFormat does (4 m); colour converted to intensity as Open3D does by default.
    std::shared_ptr<o3d::geometry::RGBDImage> rgbd =
        o3d::geometry::RGBDImage::CreateFromColorAndDepth(color, depth, 1.0, option_.depth_max_,
                                                          true);
    bool ok = true;
    if (prev_) {
      bool success;
      Eigen::Matrix4d M;
      Eigen::Matrix6d info;
      std::tie(success, M, info) = o3d::pipelines::odometry::ComputeRGBDOdometry(
          *rgbd, *prev_, *intrinsic_, Eigen::Matrix4d::Identity(), *jacobian_, option_);
      ok = success;
      if (ok) *prev_from_cur = RigidFromMatrix(M);
    }
    prev_ = rgbd;
    return ok;
  }

  std::string Describe() const override {
    return std::string("Open3D ") + OPEN3D_VERSION + " ComputeRGBDOdometry, " + method_ +
           " term, default OdometryOption (iterations 20/10/5, depth_diff_max " +
           std::to_string(option_.depth_diff_max_) + " m, depth " +
           std::to_string(option_.depth_min_) + "-" + std::to_string(option_.depth_max_) +
           " m), frame to frame";
  }

 private:
  std::string method_;
  Calibration calib_;
  std::unique_ptr<o3d::pipelines::odometry::RGBDOdometryJacobian> jacobian_;
  o3d::pipelines::odometry::OdometryOption option_;
  std::unique_ptr<o3d::camera::PinholeCameraIntrinsic> intrinsic_;
  std::shared_ptr<o3d::geometry::RGBDImage> prev_;
};

}  // namespace
}  // namespace rgbdvo::bench

int main(int argc, char** argv) {
  using namespace rgbdvo::bench;
  return RunPeerMain(argc, argv, "rgbdvo_peer_open3d", {"hybrid", "color"},
                     [](const std::string& method, const rgbdvo::Calibration& calib) {
                       return std::make_unique<Open3dPeer>(method, calib);
                     });
}
