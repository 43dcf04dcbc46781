#pragma once
// Trajectory files, written and flushed one frame at a time so nothing computed is lost.
// Poses are camera-to-world (world_from_cam); the world frame is the first camera's frame.

#include <fstream>
#include <string>

#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo {

// The time a trajectory row is stamped with.
enum class StampTime {
  kColor,  // the colour image's, the pose as estimated (distinct stamps, a row for every frame)
  kDepth,  // the paired depth image's, the pose moved there at the frame's velocity
};
// "color" or "depth"; throws std::invalid_argument naming the value.
StampTime ParseStampTime(const std::string& name);
std::string StampTimeName(StampTime stamp);

// A frame's row: kColor the estimate as is; kDepth the time result.depth_timestamp and the pose
// MoveAtVelocity(world_from_cam, velocity, depth_timestamp - timestamp) (motion_prior.hpp).
StampedPose StampRow(const FrameResult& result, StampTime stamp);

class TrajectoryWriter {
 public:
  virtual ~TrajectoryWriter() = default;
  virtual void Write(const FrameResult& result) = 0;
  // Frames given to Write but not written (see TumTrajectoryWriter).
  virtual int rows_left_out() const { return 0; }
};

// A trajectory written to a file ("-" = standard output), one flushed row at a time.
class FileTrajectoryWriter : public TrajectoryWriter {
 public:
  int rows_left_out() const override { return left_out_; }

 protected:
  // Throws naming the file.
  FileTrajectoryWriter(const std::string& path, StampTime stamp);
  // Flushes; when the write failed (disk full, ...) cuts the file back to its last whole row and
  // throws naming the file.
  void EndRow();
  // kDepth: false (and counted) for a time not after the last row's, else the time is kept as
  // the last row's. kColor: always true.
  bool Ascending(double timestamp);
  std::string path_;
  std::ofstream out_;
  StampTime stamp_;

 private:
  bool has_last_ = false;
  double last_ = 0;
  int left_out_ = 0;
  std::streamoff whole_rows_bytes_ = 0;  // the file's size after its last whole row
};

// CSV: header `frame,timestamp,tx,ty,tz,qx,qy,qz,qw,matches,inliers,status`, a row per frame.
// kDepth: `frame,timestamp,color_timestamp,tx,...`, still a row per frame; `timestamp` is the
// depth image's (two frames can share one under Pairing::kNearest; readers keep the last).
class CsvTrajectoryWriter : public FileTrajectoryWriter {
 public:
  explicit CsvTrajectoryWriter(const std::string& path, StampTime stamp = StampTime::kColor);
  void Write(const FrameResult& result) override;
};

// TUM: `timestamp tx ty tz qx qy qz qw`, a line per frame (TUM benchmark tools' format).
// kDepth: a frame whose depth stamp is not after the last line's (two colour frames paired with
// one depth frame) is left out, so the times strictly ascend as evo and the TUM tools require.
class TumTrajectoryWriter : public FileTrajectoryWriter {
 public:
  explicit TumTrajectoryWriter(const std::string& path, StampTime stamp = StampTime::kColor);
  void Write(const FrameResult& result) override;
};

// KITTI odometry: the top three rows of the 4x4 camera-to-world matrix, row-major, 12 numbers a
// line (`r11 r12 r13 tx r21 r22 r23 ty r31 r32 r33 tz`), a line per frame, no timestamps (the
// frames' order is the time). kDepth: the poses at the depth times, the same frames left out as
// from the TUM file, so the two files' lines correspond.
class KittiTrajectoryWriter : public FileTrajectoryWriter {
 public:
  explicit KittiTrajectoryWriter(const std::string& path, StampTime stamp = StampTime::kColor);
  void Write(const FrameResult& result) override;
};

}  // namespace rgbdvo
