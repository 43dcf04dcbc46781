#pragma once
// A synthetic RGB-D world for tests: a textured box room with a few textured blocks, ray-cast
// exactly (no noise unless asked), seen by pinhole cameras along a known path.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

struct PinholeCamera {
  double fx = 525, fy = 525, cx = 319.5, cy = 239.5;
  int width = 640, height = 480;
};

class SyntheticScene {
 public:
  // Deterministic for a given seed. The room spans [-2,2] x [-1.5,1.5] x [-1,4] metres (world
  // frame = first camera frame of the default path: x right, y down, z forward).
  explicit SyntheticScene(uint32_t seed = 7);
  // A hall for a ground robot (robot_path.hpp): the floor is the plane y = 0 (world y down),
  // [-4.5,4.5] x [-3.5,3.5] m in x and z, walls 2.5 m high, textured like the default room, with
  // five blocks standing on the floor beside the robot's rectangle and one feature-poor stretch:
  // a 2 m wide mat on the floor along the rectangle's side x = +1.75 and a panel on the wall
  // z = -3.5 that the robot faces there, grey with sparse low-contrast marks (about 10 per m^2),
  // where the default odometry finds 16-90 inliers instead of hundreds.
  static SyntheticScene RobotHall(uint32_t seed = 7);
  // Colour (CV_8UC3) as seen by `camera` at world_from_cam.
  cv::Mat RenderColor(const PinholeCamera& camera, const Rigid3d& world_from_cam) const;
  // Z-depth in metres (CV_32FC1) as seen by `camera` at world_from_cam.
  cv::Mat RenderDepth(const PinholeCamera& camera, const Rigid3d& world_from_cam) const;

 private:
  struct Box {
    Eigen::Vector3d lo, hi;
    bool inside_view;  // the room: seen from inside
    int texture;
  };
  // Nearest hit along the ray: distance, point, texture coordinates and texture index.
  bool Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double* t,
            cv::Vec3b* color) const;
  struct Empty {};
  explicit SyntheticScene(Empty) {}
  std::vector<Box> boxes_;
  std::vector<cv::Mat> textures_;
};

// A smooth hand-held-like path of n poses (world_from_cam), starting at identity, moving up to
// a few cm and degrees per frame.
std::vector<Rigid3d> MakeSmoothPath(int n, double step_m = 0.01, double step_deg = 0.8);

// Writes a TUM-layout folder (rgb.txt, depth.txt, rgb/, depth/, groundtruth.txt) with frames
// 1/30 s apart. Returns the timestamps. Throws naming the folder if it cannot be written.
std::vector<double> WriteTumSequence(const std::string& folder, const SyntheticScene& scene,
                                     const PinholeCamera& camera,
                                     const std::vector<Rigid3d>& world_from_cam);

}  // namespace rgbdvo
