#pragma once
// Reading trajectory files: the TUM format (`timestamp tx ty tz qx qy qz qw`, '#' comments) and
// rgbdvo's own CSV (header `frame,timestamp,tx,ty,tz,qx,qy,qz,qw,...`), told apart by the CSV
// header. Every pose in a file is camera-to-world (world_from_cam).

#include <string>
#include <vector>

#include "rgbdvo/geometry.hpp"

namespace rgbdvo {

struct StampedPose {
  double timestamp = 0;  // seconds
  Rigid3d world_from_cam = Rigid3d::Identity();
};

enum class TrajectoryFormat { kTum, kCsv };

struct Trajectory {
  std::string path;
  TrajectoryFormat format = TrajectoryFormat::kTum;
  std::vector<StampedPose> poses;  // sorted by timestamp, timestamps unique
};

// Reads a TUM or rgbdvo CSV trajectory (a CSV is recognised by a first line that names the
// columns and contains `timestamp`, `tx` and `qw`). Throws std::runtime_error naming
// `path:line` for a bad row (too few fields, not a number, a zero quaternion, a repeated
// timestamp), and naming the file for a missing or empty file. Rows need not be sorted.
Trajectory ReadTrajectory(const std::string& path);

// Writes `timestamp tx ty tz qx qy qz qw` lines; throws naming the file.
void WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses);

}  // namespace rgbdvo
