#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <system_error>
#include <vector>

#include "rgbdvo/util/temp_dir.hpp"

namespace rgbdvo::test {

double RotationErrorDeg(const Rigid3d& a, const Rigid3d& b) {
  return RotationAngleDeg(a.linear().transpose() * b.linear());
}

double TranslationError(const Rigid3d& a, const Rigid3d& b) {
  return (a.translation() - b.translation()).norm();
}

bool RigidNear(const Rigid3d& a, const Rigid3d& b, double rot_deg, double trans_m) {
  return RotationErrorDeg(a, b) <= rot_deg && TranslationError(a, b) <= trans_m;
}

Rigid3d RandomRigid(std::mt19937& rng, double angle_rad, double trans_m) {
  std::normal_distribution<double> n(0, 1);
  const Eigen::Vector3d axis = RandomVector(rng, n);
  const Eigen::Vector3d dir = RandomVector(rng, n);
  Rigid3d T = Rigid3d::Identity();
  T.linear() = AxisAngle(axis, angle_rad);
  T.translation() = dir.normalized() * trans_m;
  return T;
}

std::vector<PointPair> SynthesizePairs(std::mt19937& rng, const Rigid3d& prev_from_cur, int n,
                                       double sigma_m, double outlier_fraction) {
  std::uniform_real_distribution<double> x(-2, 2), y(-1.5, 1.5), z(1, 4);
  std::normal_distribution<double> noise(0, sigma_m > 0 ? sigma_m : 1);
  const int outliers = static_cast<int>(std::lround(outlier_fraction * n));
  std::vector<PointPair> pairs;
  for (int k = 0; k < n; ++k) {
    PointPair p;
    p.p_cur = {x(rng), y(rng), z(rng)};
    if (k < outliers) {
      p.p_prev = {x(rng), y(rng), z(rng)};
    } else {
      p.p_prev = prev_from_cur * p.p_cur;
      if (sigma_m > 0) p.p_prev += RandomVector(rng, noise);
    }
    pairs.push_back(p);
  }
  return pairs;
}

Calibration CalibFor(const PinholeCamera& cam) {
  Calibration c;
  c.fx = cam.fx;
  c.fy = cam.fy;
  c.cx = cam.cx;
  c.cy = cam.cy;
  return c;
}

namespace {

// Every folder MakeTempDir made in this process, removed when the process exits (kept with
// RGBDVO_KEEP_TEST_DIRS set, to look at what a test wrote).
class TempDirRegistry {
 public:
  ~TempDirRegistry() {
    if (std::getenv("RGBDVO_KEEP_TEST_DIRS")) return;
    for (const std::string& dir : dirs_) {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  }
  std::string Add(std::string dir) {
    const std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(dir);
    return dir;
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> dirs_;
};

TempDirRegistry& TempDirs() {
  static TempDirRegistry registry;
  return registry;
}

}  // namespace

std::string MakeTempDir(const std::string& tag) {
  return TempDirs().Add(rgbdvo::MakeTempDir("rgbdvo_test_" + tag + "_"));
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> Lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

int RunCommand(const std::string& command, std::string* output) {
  // NOLINTNEXTLINE(bugprone-command-processor): the tests run the program as a user's shell does
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf;
  output->clear();
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) output->append(buf.data(), n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string RgbdvoExe() { return RGBDVO_EXE; }
std::string RgbdvoDebugExe() { return RGBDVO_DEBUG_EXE; }
std::string SourceDir() { return RGBDVO_SOURCE_DIR; }

std::pair<int, int> PngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), 24);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(sig, sig + 8, h)) return {0, 0};
  auto be32 = [&](int at) {
    return (h[at] << 24) | (h[at + 1] << 16) | (h[at + 2] << 8) | h[at + 3];
  };
  return {be32(16), be32(20)};
}

}  // namespace rgbdvo::test
