#include "rgbdvo/pipeline/trajectory_writer.hpp"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "rgbdvo/geometry/motion_prior.hpp"

namespace rgbdvo {

StampTime ParseStampTime(const std::string& name) {
  if (name == "color") return StampTime::kColor;
  if (name == "depth") return StampTime::kDepth;
  throw std::invalid_argument("unknown stamp '" + name + "' (expected color or depth)");
}

std::string StampTimeName(StampTime stamp) {
  return stamp == StampTime::kDepth ? "depth" : "color";
}

StampedPose StampRow(const FrameResult& r, StampTime stamp) {
  if (stamp == StampTime::kColor) return {r.timestamp, r.world_from_cam};
  Rigid3d moved = MoveAtVelocity(r.world_from_cam, r.velocity, r.depth_timestamp - r.timestamp);
  moved.linear() = NearestRotation(moved.linear());
  return {r.depth_timestamp, moved};
}

FileTrajectoryWriter::FileTrajectoryWriter(const std::string& path, StampTime stamp)
    : path_(path), stamp_(stamp) {
  if (path == "-") {
    out_.std::basic_ios<char>::rdbuf(std::cout.rdbuf());
    out_.clear();
  } else {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // failure shows below
    out_.open(path, std::ios::out | std::ios::trunc);
    if (!out_) throw std::runtime_error(path + ": cannot open for writing");
  }
  out_ << std::fixed;
}

bool FileTrajectoryWriter::Ascending(double timestamp) {
  if (stamp_ == StampTime::kColor) return true;
  if (has_last_ && !(timestamp > last_)) {
    ++left_out_;
    return false;
  }
  has_last_ = true;
  last_ = timestamp;
  return true;
}

void FileTrajectoryWriter::EndRow() {
  out_.flush();
  if (out_) {
    if (path_ != "-") whole_rows_bytes_ = out_.tellp();
    return;
  }
  if (path_ == "-")
    throw std::runtime_error("standard output: write failed (pipe closed or disk full?)");
  // A write cut short leaves part of a row: closing may write more of it, so cut after closing.
  out_.close();
  std::error_code ec;
  std::filesystem::resize_file(path_, static_cast<std::uintmax_t>(whole_rows_bytes_), ec);
  throw std::runtime_error(path_ + ": write failed (disk full or file gone?); the file ends at " +
                           "its last whole row");
}

CsvTrajectoryWriter::CsvTrajectoryWriter(const std::string& path, StampTime stamp)
    : FileTrajectoryWriter(path, stamp) {
  out_ << "frame,timestamp," << (stamp_ == StampTime::kDepth ? "color_timestamp," : "")
       << "tx,ty,tz,qx,qy,qz,qw,matches,inliers,status\n";
  EndRow();
}

void CsvTrajectoryWriter::Write(const FrameResult& r) {
  const StampedPose row = StampRow(r, stamp_);
  out_ << r.frame << ',' << std::setprecision(6) << row.timestamp << ',';
  if (stamp_ == StampTime::kDepth) out_ << r.timestamp << ',';
  WritePoseFields(out_, row.world_from_cam, ',');
  out_ << ',' << r.matches << ',' << r.inliers << ',' << r.StatusString() << '\n';
  EndRow();
}

TumTrajectoryWriter::TumTrajectoryWriter(const std::string& path, StampTime stamp)
    : FileTrajectoryWriter(path, stamp) {
  out_ << "# timestamp tx ty tz qx qy qz qw (camera-to-world"
       << (stamp_ == StampTime::kDepth ? " at the depth images' times" : "") << ", rgbdvo)\n";
  EndRow();
}

void TumTrajectoryWriter::Write(const FrameResult& r) {
  const StampedPose row = StampRow(r, stamp_);
  if (!Ascending(row.timestamp)) return;
  WriteTumLine(out_, row.timestamp, row.world_from_cam);
  EndRow();
}

KittiTrajectoryWriter::KittiTrajectoryWriter(const std::string& path, StampTime stamp)
    : FileTrajectoryWriter(path, stamp) {
  out_ << std::setprecision(9);
  out_.unsetf(std::ios::floatfield);  // general notation: KITTI tools read either
}

void KittiTrajectoryWriter::Write(const FrameResult& r) {
  const StampedPose row = StampRow(r, stamp_);
  if (!Ascending(row.timestamp)) return;
  const Eigen::Matrix4d M = row.world_from_cam.matrix();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) out_ << M(row, col) << (row == 2 && col == 3 ? '\n' : ' ');
  EndRow();
}

}  // namespace rgbdvo
