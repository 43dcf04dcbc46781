#include "rgbdvo/synthetic/robot_path.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace fs = std::filesystem;

namespace rgbdvo {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct PlanarPose {
  double x, z, yaw;  // yaw about world +y; heading (sin yaw, 0, cos yaw)
};

// The pose at distance s along the rounded rectangle (any s: the path repeats every lap).
PlanarPose PoseAt(const RobotPathOptions& o, double s) {
  const double r = o.turn_radius_m, arc = M_PI / 2 * r;
  const double straight[2] = {o.size_z_m - 2 * r, o.size_x_m - 2 * r};
  s = std::fmod(s, o.LapLength());
  if (s < 0) s += o.LapLength();
  PlanarPose p{-o.size_x_m / 2, -(o.size_z_m / 2 - r), 0.0};
  for (int side = 0; side < 4; ++side) {
    const double dx = std::sin(p.yaw), dz = std::cos(p.yaw);
    const double len = straight[side % 2];
    if (s <= len) return {p.x + s * dx, p.z + s * dz, p.yaw};
    p.x += len * dx, p.z += len * dz, s -= len;
    // A right turn (yaw grows) about the centre r to the heading's right, (cos yaw, -sin yaw).
    const double cx = p.x + r * dz, cz = p.z - r * dx;
    const double phi = std::min(s, arc) / r, yaw = p.yaw + phi;
    const PlanarPose q{cx - r * std::cos(yaw), cz + r * std::sin(yaw), yaw};
    if (s <= arc) return q;
    p = q, s -= arc;
  }
  return p;  // not reached: s < LapLength()
}

}  // namespace

void RobotPathOptions::Check() const {
  if (!(turn_radius_m > 0))
    throw std::invalid_argument("RobotPathOptions.turn_radius_m must be > 0");
  if (!(size_x_m >= 2 * turn_radius_m) || !(size_z_m >= 2 * turn_radius_m))
    throw std::invalid_argument(
        "RobotPathOptions.size_x_m and .size_z_m must be at least 2 * turn_radius_m");
  if (!(speed_mps > 0)) throw std::invalid_argument("RobotPathOptions.speed_mps must be > 0");
  if (!(frame_rate_hz > 0))
    throw std::invalid_argument("RobotPathOptions.frame_rate_hz must be > 0");
  if (!(camera_height_m > 0))
    throw std::invalid_argument("RobotPathOptions.camera_height_m must be > 0");
  if (!(std::abs(pitch_deg) < 90) || !(std::abs(roll_deg) < 90))
    throw std::invalid_argument("RobotPathOptions.pitch_deg and .roll_deg must be within 90");
}

double RobotPathOptions::LapLength() const {
  return 2 * (size_x_m + size_z_m) - 8 * turn_radius_m + 2 * M_PI * turn_radius_m;
}

int RobotPathOptions::LapFrames() const {
  return static_cast<int>(std::lround(LapLength() / speed_mps * frame_rate_hz));
}

std::vector<Rigid3d> MakeRobotPath(const RobotPathOptions& o, int n) {
  o.Check();
  const Eigen::Matrix3d mount = (Eigen::AngleAxisd(-o.pitch_deg * kDeg, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(o.roll_deg * kDeg, Eigen::Vector3d::UnitZ()))
                                    .toRotationMatrix();
  std::vector<Rigid3d> path;
  for (int k = 0; k < n; ++k) {
    const PlanarPose p = PoseAt(o, o.start_m + k * o.speed_mps / o.frame_rate_hz);
    Rigid3d T = Rigid3d::Identity();
    T.linear() = Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitY()).toRotationMatrix() * mount;
    T.translation() = Eigen::Vector3d(p.x, -o.camera_height_m, p.z);
    path.push_back(T);
  }
  return path;
}

RobotFloorTruth RobotIrFloorTruth(const RobotPathOptions& path,
                                  const SyntheticKinectOptions& kinect) {
  const Rigid3d world_from_color = MakeRobotPath(path, 1)[0];
  const Eigen::Vector3d n = world_from_color.linear().transpose() * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d ir_centre = world_from_color * kinect.ir_in_color;
  RobotFloorTruth t;
  t.height_m = -ir_centre.y();  // the floor is y = 0
  t.pitch_deg = std::atan2(n.z(), n.y()) / kDeg;
  t.roll_deg = std::asin(n.x()) / kDeg;
  return t;
}

SyntheticKinectOptions RobotKinectOptions(uint32_t seed) {
  SyntheticKinectOptions o;
  o.depth_noise = true;
  o.noise_seed = seed;
  o.camera_acceleration = true;
  return o;
}

std::vector<Rigid3d> WriteRobotRecording(const std::string& folder, const RobotPathOptions& path,
                                         int n, uint32_t seed) {
  const SyntheticKinectOptions kinect = RobotKinectOptions(seed);
  std::vector<Rigid3d> poses = WriteSyntheticKinectRecording(
      folder, SyntheticScene::RobotHall(seed), kinect, MakeRobotPath(path, n));
  const RobotFloorTruth t = RobotIrFloorTruth(path, kinect);
  std::ofstream out(fs::path(folder) / "robot.txt");
  out << std::setprecision(8);
  out << "# rgbdvo synthetic ground robot (robot_path.hpp): the true floor under the IR camera,\n"
         "# as FitFloor reports it (floor_plane.hpp), and the path's constants.\n"
      << "ir_height_m: " << t.height_m << "\n"
      << "ir_pitch_deg: " << t.pitch_deg << "\n"
      << "ir_roll_deg: " << t.roll_deg << "\n"
      << "color_height_m: " << path.camera_height_m << "\n"
      << "mount_pitch_deg: " << path.pitch_deg << "\n"
      << "mount_roll_deg: " << path.roll_deg << "\n"
      << "speed_mps: " << path.speed_mps << "\n"
      << "turn_rate_deg_per_s: " << path.speed_mps / path.turn_radius_m / kDeg << "\n"
      << "lap_m: " << path.LapLength() << "\n"
      << "lap_frames: " << path.LapFrames() << "\n"
      << "start_m: " << path.start_m << "\n"
      << "frames: " << n << "\n"
      << "seed: " << seed << "\n";
  if (!out.flush()) throw std::runtime_error(folder + "/robot.txt: cannot write");
  return poses;
}

}  // namespace rgbdvo
