#pragma once
// A ground robot's recording with ground truth: a Kinect rigidly mounted on a robot
// that drives a rectangle with rounded corners on the floor of SyntheticScene::RobotHall, like
// the laps of the paper's Fig. 5. The motion is strictly planar: only x, z and the yaw of the
// robot change; the camera's height above the floor, its mount pitch and roll stay fixed.

#include <cstdint>
#include <string>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/synthetic/synthetic_kinect.hpp"

namespace rgbdvo {

struct RobotPathOptions {
  // The rectangle's centre lines, centred on the hall's origin: 5 m along z and 3.5 m along x,
  // with quarter circles of turn_radius_m at the corners: 15.97 m per lap, 1 m from the end
  // walls and 2.75 m from the side walls, so the wall ahead stays within the Kinect's range
  // (under 6 m away).
  double size_x_m = 3.5;
  double size_z_m = 5.0;
  // 0.4 m/s (a slow indoor robot: 1.3 cm per frame at 30 Hz) on a 0.6 m radius turns at
  // 0.67 rad/s = 38 deg/s (1.3 degrees per frame) and accelerates sideways by v^2 / r =
  // 0.27 m/s^2, which the accelerometer sees.
  double turn_radius_m = 0.6;
  double speed_mps = 0.4;
  double frame_rate_hz = 30.0;
  // The colour camera's centre above the floor (a robot's deck), its mount pitch down (so that
  // the floor fills the image below the horizon, 111 px above the centre at 12 degrees) and a
  // small roll (an imperfect mount), degrees. The camera's x axis rolls towards its +y.
  double camera_height_m = 0.6;
  double pitch_deg = 12.0;
  double roll_deg = 1.0;
  // Distance along the path at frame 0, m: 0 is the start of the side x = -1.75 (heading +z);
  // the robot turns right (yaw grows) at each corner: +z, +x, -z (the feature-poor side), -x.
  double start_m = 0.0;
  void Check() const;        // throws std::invalid_argument naming the field
  double LapLength() const;  // m
  int LapFrames() const;     // frames of one lap, rounded
};

// world_from_color of n frames 1 / frame_rate_hz apart in SyntheticScene::RobotHall's frame
// (floor y = 0, y down): world_from_color = [R_y(yaw) R_x(-pitch) R_z(roll), (x, -height, z)].
std::vector<Rigid3d> MakeRobotPath(const RobotPathOptions& options, int n);

// The floor as FitFloor (floor_plane.hpp) reports it for the IR camera, whose frame the
// odometry measures: height of its centre above the floor, m, and pitch = atan2(n_z, n_y),
// roll = asin(n_x) of the floor's downward normal n in its frame, degrees. The same in every
// frame of a planar path.
struct RobotFloorTruth {
  double height_m = 0, pitch_deg = 0, roll_deg = 0;
};
RobotFloorTruth RobotIrFloorTruth(const RobotPathOptions& path,
                                  const SyntheticKinectOptions& kinect);

// The Kinect options of a robot recording: the defaults, plus depth noise and the camera's
// acceleration in the accelerometer entries.
SyntheticKinectOptions RobotKinectOptions(uint32_t seed);

// Writes a robot recording of n frames (WriteSyntheticKinectRecording over MakeRobotPath in
// SyntheticScene::RobotHall(seed), with RobotKinectOptions(seed)) and robot.txt: the path's
// constants and RobotIrFloorTruth as YAML `key: value` lines. Returns the colour camera poses.
std::vector<Rigid3d> WriteRobotRecording(const std::string& folder, const RobotPathOptions& path,
                                         int n, uint32_t seed = 7);

}  // namespace rgbdvo
