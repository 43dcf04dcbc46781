#pragma once
// Reading trajectory files: the TUM format (`timestamp tx ty tz qx qy qz qw`, '#' comments) and
// rgbdvo's own CSV (header `frame,timestamp,tx,ty,tz,qx,qy,qz,qw,...`), told apart by the CSV
// header. Every pose in a file is camera-to-world (world_from_cam).

#include <ostream>
#include <string>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"

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
  int repeated_timestamps = 0;     // rows dropped because a later row had the same timestamp
};

// Reads a TUM or rgbdvo CSV trajectory (a CSV is recognised by a first line that names the
// columns and contains `timestamp`, `tx` and `qw`). Throws std::runtime_error naming
// `path:line` for a bad row (too few fields, not a number, a zero quaternion), and naming the
// file for a missing or empty file. Rows need not be sorted. Of rows with the same timestamp
// the last one is kept, as in the TUM tools.
Trajectory ReadTrajectory(const std::string& path);

// Sorts by time (stable) and keeps the last of poses with the same timestamp, as ReadTrajectory
// does; returns how many were dropped. For poses that did not come from a file (a run's), so
// that they count and match as the same trajectory read back would.
int KeepLastOfEachTime(std::vector<StampedPose>* poses);

// The pose part of a trajectory row, `tx ty tz qx qy qz qw` with `sep` between the fields,
// fixed-point: 6 decimals for the position (micrometres), 7 for the unit quaternion. The
// stream's format flags are left as they were.
void WritePoseFields(std::ostream& out, const Rigid3d& world_from_cam, char sep);

// One TUM line, `timestamp tx ty tz qx qy qz qw` and a newline, the time with 6 decimals
// (microseconds): every TUM file rgbdvo writes (trajectories, ground truth, benchmarks).
void WriteTumLine(std::ostream& out, double timestamp, const Rigid3d& world_from_cam);

// Writes `timestamp tx ty tz qx qy qz qw` lines; throws naming the file.
void WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses);

}  // namespace rgbdvo
