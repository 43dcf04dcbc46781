#include "rgbdvo/synthetic/synthetic_kinect.hpp"

#include <libfreenect.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "rgbdvo/capture/fakenect_recorder.hpp"
#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"
#include "rgbdvo/sources/fakenect_files.hpp"

namespace fs = std::filesystem;

namespace rgbdvo {
void SyntheticKinectOptions::Check() const {
  if (ir_in_color.z() != 0.0)
    throw std::invalid_argument("SyntheticKinectOptions.ir_in_color.z must be 0");
  if (!(reference_depth_m > 0))
    throw std::invalid_argument("SyntheticKinectOptions.reference_depth_m must be > 0");
  if (period_us <= 1000)
    throw std::invalid_argument("SyntheticKinectOptions.period_us must be > 1000");
  if (color.width <= 0 || color.height <= 0 || ir.width <= 0 || ir.height <= 0)
    throw std::invalid_argument("SyntheticKinectOptions.color and .ir sizes must be > 0");
}

void AddKinectDepthNoise(cv::RNG& rng, cv::Mat* depth_m) {
  for (auto it = depth_m->begin<float>(); it != depth_m->end<float>(); ++it)
    if (*it > 0) *it += static_cast<float>(rng.gaussian(kKinectDepthNoiseCoeff * *it * *it));
}

Calibration SyntheticKinectCalibration(const SyntheticKinectOptions& o, bool depth_aware) {
  o.Check();
  Calibration c;
  c.A = o.ir.fx / o.color.fx;
  c.C = o.ir.fy / o.color.fy;
  if (depth_aware) {
    c.B = o.ir.cx - c.A * o.color.cx;
    c.D = o.ir.cy - c.C * o.color.cy;
    c.s_u = -o.ir.fx * o.ir_in_color.x();
    c.s_v = -o.ir.fy * o.ir_in_color.y();
  } else {  // eq. 1 folds the disparity at the reference depth into B and D
    c.B = o.ir.cx - c.A * o.color.cx - o.ir.fx * o.ir_in_color.x() / o.reference_depth_m;
    c.D = o.ir.cy - c.C * o.color.cy - o.ir.fy * o.ir_in_color.y() / o.reference_depth_m;
  }
  c.fx = o.ir.fx;
  c.fy = o.ir.fy;
  c.cx = o.ir.cx;
  c.cy = o.ir.cy;
  c.min_depth_m = 0.4;
  c.max_depth_m = 8.0;
  c.description =
      depth_aware
          ? "rgbdvo synthetic Kinect: IR camera offset from the colour camera; depth-aware "
            "mapping, exact at every depth (synthetic_kinect.hpp)"
          : "rgbdvo synthetic Kinect: IR camera offset from the colour camera; A-D exact at " +
                std::to_string(o.reference_depth_m) + " m (synthetic_kinect.hpp)";
  return c;
}

std::vector<Rigid3d> MakeKinectRangePath(int n) {
  std::vector<Rigid3d> path = MakeSmoothPath(n);
  Rigid3d forward = Rigid3d::Identity();
  forward.translation() = Eigen::Vector3d(0, 0, 2.0);
  for (Rigid3d& p : path) p = forward * p;
  return path;
}

std::vector<Rigid3d> WriteSyntheticKinectRecording(const std::string& folder,
                                                   const SyntheticScene& scene,
                                                   const SyntheticKinectOptions& o,
                                                   const std::vector<Rigid3d>& world_from_color) {
  const Calibration calib = SyntheticKinectCalibration(o);
  FakenectRecorder recorder(folder);
  Rigid3d color_from_ir = Rigid3d::Identity();
  color_from_ir.translation() = o.ir_in_color;
  std::ofstream gt(fs::path(folder) / "groundtruth.txt");
  if (!gt) throw std::runtime_error(folder + "/groundtruth.txt: cannot create");
  gt << "# colour camera poses relative to the first (TUM format; rgbdvo's poses are the colour "
        "camera's)\n# timestamp tx ty tz qx qy qz qw\n"
     << std::fixed;
  std::vector<Rigid3d> color_poses;
  const Rigid3d color0_from_world =
      world_from_color.empty() ? Rigid3d::Identity() : world_from_color.front().inverse();
  cv::RNG noise(o.noise_seed);
  const size_t n = world_from_color.size();
  const double dt = static_cast<double>(o.period_us) * 1e-6;
  for (size_t k = 0; k < world_from_color.size(); ++k) {
    const int64_t t = o.start_us + static_cast<int64_t>(k) * o.period_us;
    const uint32_t ts = static_cast<uint32_t>(500 + 2000000 * k);
    const Rigid3d world_from_ir = world_from_color[k] * color_from_ir;
    cv::Mat rgb;
    cv::cvtColor(scene.RenderColor(o.color, world_from_color[k]), rgb, cv::COLOR_BGR2RGB);
    recorder.AddColor(t, ts, rgb.ptr<uint8_t>(), rgb.cols, rgb.rows);
    if (o.accelerometer) {
      // Gravity is +y (down) in the world frame; in the Kinect's axes (kinect_accelerometer.hpp).
      Eigen::Vector3d apparent_in_g(0, 1, 0);
      if (o.camera_acceleration && n >= 3) {  // at the ends, the acceleration next to them
        const size_t i = std::clamp<size_t>(k, 1, n - 2);
        apparent_in_g -=
            (world_from_color[i + 1].translation() - 2 * world_from_color[i].translation() +
             world_from_color[i - 1].translation()) /
            (dt * dt * kStandardGravity);
      }
      const Eigen::Vector3d g =
          KinectAccelFromApparentGravity(world_from_color[k].linear().transpose() * apparent_in_g) *
          kKinectAccelCountsPerG;
      freenect_raw_tilt_state state{};
      state.accelerometer_x = static_cast<int16_t>(std::lround(g.x()));
      state.accelerometer_y = static_cast<int16_t>(std::lround(g.y()));
      state.accelerometer_z = static_cast<int16_t>(std::lround(g.z()));
      state.tilt_status = TILT_STATUS_STOPPED;
      recorder.AddAccel(t + 300, ts, &state, sizeof(state));
    }
    cv::Mat depth = scene.RenderDepth(o.ir, world_from_ir);
    if (o.depth_noise) AddKinectDepthNoise(noise, &depth);
    const cv::Mat raw = KinectRawFromDepth(depth);
    recorder.AddDepth(t + 1000, ts + 1000, raw.ptr<uint16_t>(), raw.cols, raw.rows);

    const Rigid3d color0_from_colork = color0_from_world * world_from_color[k];
    color_poses.push_back(color0_from_colork);
    WriteTumLine(gt, static_cast<double>(t + 1000) * 1e-6, color0_from_colork);
  }
  if (!gt.flush()) throw std::runtime_error(folder + "/groundtruth.txt: write failed");
  SaveCalibration(calib, (fs::path(folder) / "calib.yaml").string());
  SaveCalibration(SyntheticKinectCalibration(o, true),
                  (fs::path(folder) / "calib_depth_aware.yaml").string());
  return color_poses;
}

}  // namespace rgbdvo
