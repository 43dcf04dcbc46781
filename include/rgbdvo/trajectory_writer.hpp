#pragma once
// Trajectory files, written and flushed one frame at a time so nothing computed is lost.
// Poses are camera-to-world (world_from_cam); the world frame is the first camera's frame.

#include <fstream>
#include <string>

#include "rgbdvo/odometry.hpp"

namespace rgbdvo {

class TrajectoryWriter {
 public:
  virtual ~TrajectoryWriter() = default;
  virtual void Write(const FrameResult& result) = 0;
};

// CSV: header `frame,timestamp,tx,ty,tz,qx,qy,qz,qw,matches,inliers,status`, a row per frame.
class CsvTrajectoryWriter : public TrajectoryWriter {
 public:
  // "-" = standard output. Throws naming the file when it cannot be opened.
  explicit CsvTrajectoryWriter(const std::string& path);
  void Write(const FrameResult& result) override;

 private:
  std::string path_;
  std::ofstream out_;
};

// TUM: `timestamp tx ty tz qx qy qz qw`, a line per frame (TUM benchmark tools' format).
class TumTrajectoryWriter : public TrajectoryWriter {
 public:
  // "-" = standard output. Throws naming the file when it cannot be opened.
  explicit TumTrajectoryWriter(const std::string& path);
  void Write(const FrameResult& result) override;

 private:
  std::string path_;
  std::ofstream out_;
};

// KITTI odometry: the top three rows of the 4x4 camera-to-world matrix, row-major, 12 numbers a
// line (`r11 r12 r13 tx r21 r22 r23 ty r31 r32 r33 tz`), a line per frame, no timestamps (the
// frames' order is the time).
class KittiTrajectoryWriter : public TrajectoryWriter {
 public:
  // "-" = standard output. Throws naming the file when it cannot be opened.
  explicit KittiTrajectoryWriter(const std::string& path);
  void Write(const FrameResult& result) override;

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace rgbdvo
