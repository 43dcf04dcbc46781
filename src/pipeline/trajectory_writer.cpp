#include "rgbdvo/pipeline/trajectory_writer.hpp"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "rgbdvo/io/trajectory_io.hpp"

namespace rgbdvo {

FileTrajectoryWriter::FileTrajectoryWriter(const std::string& path) : path_(path) {
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

void FileTrajectoryWriter::EndRow() {
  out_.flush();
  if (!out_)
    throw std::runtime_error((path_ == "-" ? std::string("standard output") : path_) +
                             ": write failed (disk full, file gone or pipe closed?)");
}

CsvTrajectoryWriter::CsvTrajectoryWriter(const std::string& path) : FileTrajectoryWriter(path) {
  out_ << "frame,timestamp,tx,ty,tz,qx,qy,qz,qw,matches,inliers,status\n";
  EndRow();
}

void CsvTrajectoryWriter::Write(const FrameResult& r) {
  out_ << r.frame << ',' << std::setprecision(6) << r.timestamp << ',';
  WritePoseFields(out_, r.world_from_cam, ',');
  out_ << ',' << r.matches << ',' << r.inliers << ',' << r.StatusString() << '\n';
  EndRow();
}

TumTrajectoryWriter::TumTrajectoryWriter(const std::string& path) : FileTrajectoryWriter(path) {
  out_ << "# timestamp tx ty tz qx qy qz qw (camera-to-world, rgbdvo)\n";
  EndRow();
}

void TumTrajectoryWriter::Write(const FrameResult& r) {
  WriteTumLine(out_, r.timestamp, r.world_from_cam);
  EndRow();
}

KittiTrajectoryWriter::KittiTrajectoryWriter(const std::string& path) : FileTrajectoryWriter(path) {
  out_ << std::setprecision(9);
  out_.unsetf(std::ios::floatfield);  // general notation: KITTI tools read either
}

void KittiTrajectoryWriter::Write(const FrameResult& r) {
  const Eigen::Matrix4d M = r.world_from_cam.matrix();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) out_ << M(row, col) << (row == 2 && col == 3 ? '\n' : ' ');
  EndRow();
}

}  // namespace rgbdvo
