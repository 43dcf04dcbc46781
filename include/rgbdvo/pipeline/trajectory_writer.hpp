#pragma once
// Trajectory files, written and flushed one frame at a time so nothing computed is lost.
// Poses are camera-to-world (world_from_cam); the world frame is the first camera's frame.

#include <fstream>
#include <string>

#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo {

class TrajectoryWriter {
 public:
  virtual ~TrajectoryWriter() = default;
  virtual void Write(const FrameResult& result) = 0;
};

// A trajectory written to a file ("-" = standard output), one flushed row at a time.
class FileTrajectoryWriter : public TrajectoryWriter {
 protected:
  explicit FileTrajectoryWriter(const std::string& path);  // throws naming the file
  void EndRow();  // flushes; throws naming the file when the write failed (disk full, ...)
  std::string path_;
  std::ofstream out_;
};

// CSV: header `frame,timestamp,tx,ty,tz,qx,qy,qz,qw,matches,inliers,status`, a row per frame.
class CsvTrajectoryWriter : public FileTrajectoryWriter {
 public:
  explicit CsvTrajectoryWriter(const std::string& path);
  void Write(const FrameResult& result) override;
};

// TUM: `timestamp tx ty tz qx qy qz qw`, a line per frame (TUM benchmark tools' format).
class TumTrajectoryWriter : public FileTrajectoryWriter {
 public:
  explicit TumTrajectoryWriter(const std::string& path);
  void Write(const FrameResult& result) override;
};

// KITTI odometry: the top three rows of the 4x4 camera-to-world matrix, row-major, 12 numbers a
// line (`r11 r12 r13 tx r21 r22 r23 ty r31 r32 r33 tz`), a line per frame, no timestamps (the
// frames' order is the time).
class KittiTrajectoryWriter : public FileTrajectoryWriter {
 public:
  explicit KittiTrajectoryWriter(const std::string& path);
  void Write(const FrameResult& result) override;
};

}  // namespace rgbdvo
