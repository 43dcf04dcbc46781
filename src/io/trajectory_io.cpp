#include "rgbdvo/io/trajectory_io.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/io/text.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

std::vector<std::string> Split(const std::string& line, bool csv) {
  std::vector<std::string> fields;
  if (csv) {
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(Trim(f));
  } else {
    std::istringstream s(line);
    for (std::string f; s >> f;) fields.push_back(f);
  }
  return fields;
}

}  // namespace

Trajectory ReadTrajectory(const std::string& path) {
  std::istringstream in(ReadTextFile(path, "trajectory file", kMaxTrajectoryFileBytes));
  Trajectory traj;
  traj.path = path;
  static const char* kNames[] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  std::map<std::string, int> column;  // CSV: column of each field
  bool first = true;
  int line_no = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++line_no;
    const std::string line = Trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(line_no);
    if (first) {
      first = false;
      const std::vector<std::string> header = Split(line, true);
      if (std::find(header.begin(), header.end(), "timestamp") != header.end()) {
        traj.format = TrajectoryFormat::kCsv;
        for (size_t i = 0; i < header.size(); ++i) column[header[i]] = static_cast<int>(i);
        for (const char* name : kNames)
          if (!column.count(name))
            throw std::runtime_error(where + ": CSV header lacks column '" + name + "'");
        continue;
      }
    }
    const bool csv = traj.format == TrajectoryFormat::kCsv;
    const std::vector<std::string> f = Split(line, csv);
    double v[8];
    for (int k = 0; k < 8; ++k) {
      const size_t col = csv ? static_cast<size_t>(column[kNames[k]]) : static_cast<size_t>(k);
      if (col >= f.size())
        throw std::runtime_error(where + ": expected " +
                                 (csv ? std::to_string(column.size()) + " comma-separated" : "8") +
                                 " fields (timestamp tx ty tz qx qy qz qw), found " +
                                 std::to_string(f.size()));
      v[k] = ParseNumber(f[col], where + ": " + kNames[k]);
    }
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (q.norm() < 1e-6) throw std::runtime_error(where + ": quaternion has zero norm");
    traj.poses.push_back({v[0], MakeRigid(q, {v[1], v[2], v[3]})});
  }
  if (traj.poses.empty())
    throw std::runtime_error(path + ": no poses (empty file or only comments/header)");
  traj.repeated_timestamps = KeepLastOfEachTime(&traj.poses);
  return traj;
}

int KeepLastOfEachTime(std::vector<StampedPose>* poses) {
  // Sort by time keeping the given order among equal times, then keep the last of each time.
  std::stable_sort(poses->begin(), poses->end(), [](const StampedPose& a, const StampedPose& b) {
    return a.timestamp < b.timestamp;
  });
  std::vector<StampedPose> unique;
  unique.reserve(poses->size());
  for (size_t k = 0; k < poses->size(); ++k)
    if (k + 1 == poses->size() || (*poses)[k + 1].timestamp != (*poses)[k].timestamp)
      unique.push_back((*poses)[k]);
  const int dropped = static_cast<int>(poses->size() - unique.size());
  *poses = std::move(unique);
  return dropped;
}

void WritePoseFields(std::ostream& out, const Rigid3d& T, char sep) {
  const std::ios::fmtflags flags = out.flags();
  const std::streamsize precision = out.precision();
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d& t = T.translation();
  out << std::fixed << std::setprecision(6) << t.x() << sep << t.y() << sep << t.z() << sep
      << std::setprecision(7) << q.x() << sep << q.y() << sep << q.z() << sep << q.w();
  out.flags(flags);
  out.precision(precision);
}

void WriteTumLine(std::ostream& out, double timestamp, const Rigid3d& world_from_cam) {
  const std::ios::fmtflags flags = out.flags();
  const std::streamsize precision = out.precision();
  out << std::fixed << std::setprecision(6) << timestamp << ' ';
  out.flags(flags);
  out.precision(precision);
  WritePoseFields(out, world_from_cam, ' ');
  out << '\n';
}

void WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << "# timestamp tx ty tz qx qy qz qw (camera-to-world)\n";
  for (const StampedPose& p : poses) WriteTumLine(out, p.timestamp, p.world_from_cam);
  out.flush();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace rgbdvo
