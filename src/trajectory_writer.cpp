#include "rgbdvo/trajectory_writer.hpp"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <stdexcept>

namespace rgbdvo {
namespace {

// Opens `path` for writing, or points `out` at standard output for "-".
void OpenOrThrow(std::ofstream& out, const std::string& path) {
  if (path == "-") {
    out.std::basic_ios<char>::rdbuf(std::cout.rdbuf());
    out.clear();
  } else {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // failure shows below
    out.open(path, std::ios::out | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
  }
  out << std::fixed;
}

void WritePose(std::ostream& out, const Rigid3d& T, char sep) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d& t = T.translation();
  out << std::setprecision(6) << t.x() << sep << t.y() << sep << t.z() << sep
      << std::setprecision(7) << q.x() << sep << q.y() << sep << q.z() << sep << q.w();
}

void FlushOrThrow(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out)
    throw std::runtime_error((path == "-" ? std::string("standard output") : path) +
                             ": write failed (disk full, file gone or pipe closed?)");
}

}  // namespace

CsvTrajectoryWriter::CsvTrajectoryWriter(const std::string& path) : path_(path) {
  OpenOrThrow(out_, path_);
  out_ << "frame,timestamp,tx,ty,tz,qx,qy,qz,qw,matches,inliers,status\n";
  FlushOrThrow(out_, path_);
}

void CsvTrajectoryWriter::Write(const FrameResult& r) {
  out_ << r.frame << ',' << std::setprecision(6) << r.timestamp << ',';
  WritePose(out_, r.world_from_cam, ',');
  out_ << ',' << r.matches << ',' << r.inliers << ',' << r.StatusString() << '\n';
  FlushOrThrow(out_, path_);
}

TumTrajectoryWriter::TumTrajectoryWriter(const std::string& path) : path_(path) {
  OpenOrThrow(out_, path_);
  out_ << "# timestamp tx ty tz qx qy qz qw (camera-to-world, rgbdvo)\n";
  FlushOrThrow(out_, path_);
}

void TumTrajectoryWriter::Write(const FrameResult& r) {
  out_ << std::setprecision(6) << r.timestamp << ' ';
  WritePose(out_, r.world_from_cam, ' ');
  out_ << '\n';
  FlushOrThrow(out_, path_);
}

KittiTrajectoryWriter::KittiTrajectoryWriter(const std::string& path) : path_(path) {
  OpenOrThrow(out_, path_);
  out_ << std::setprecision(9);
  out_.unsetf(std::ios::floatfield);  // general notation: KITTI tools read either
}

void KittiTrajectoryWriter::Write(const FrameResult& r) {
  const Eigen::Matrix4d M = r.world_from_cam.matrix();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) out_ << M(row, col) << (row == 2 && col == 3 ? '\n' : ' ');
  FlushOrThrow(out_, path_);
}

}  // namespace rgbdvo
