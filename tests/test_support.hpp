#pragma once
// Shared test helpers: pose comparison, random motions, synthetic point pairs, running the CLI.

#include <random>
#include <string>
#include <utility>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/odometry/point_pairs.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"

namespace rgbdvo::test {

// Rotation angle (deg) and translation distance (m) between two poses.
double RotationErrorDeg(const Rigid3d& a, const Rigid3d& b);
double TranslationError(const Rigid3d& a, const Rigid3d& b);
// True when a and b differ by at most rot_deg and trans_m; prints both on failure via INFO.
bool RigidNear(const Rigid3d& a, const Rigid3d& b, double rot_deg, double trans_m);

// A random rigid motion with rotation angle `angle_rad` about a random axis and a translation
// of norm `trans_m` in a random direction.
Rigid3d RandomRigid(std::mt19937& rng, double angle_rad, double trans_m);

// Three draws of `d` as a vector, one statement each so that every compiler draws them in the
// same order (a call's arguments are evaluated in an order of the compiler's choosing); the last
// coordinate is drawn first, the order the tests' figures were measured with.
template <typename Distribution>
Eigen::Vector3d RandomVector(std::mt19937& rng, Distribution& d) {
  const double z = d(rng);
  const double y = d(rng);
  const double x = d(rng);
  return {x, y, z};
}

// n pairs p_prev = prev_from_cur * p_cur (+ isotropic Gaussian noise sigma_m per coordinate on
// p_prev), p_cur spread over a 4 x 3 x 3 m volume in front of the camera. The first
// round(outlier_fraction*n) pairs get an unrelated p_prev.
std::vector<PointPair> SynthesizePairs(std::mt19937& rng, const Rigid3d& prev_from_cur, int n,
                                       double sigma_m, double outlier_fraction);

// The calibration of registered depth seen by `cam`: identity mapping, K of the colour camera.
Calibration CalibFor(const PinholeCamera& cam);

// A fresh empty temporary folder, unique per call, removed with its contents when the test
// process exits (unless RGBDVO_KEEP_TEST_DIRS is set).
std::string MakeTempDir(const std::string& tag);

// A file's bytes ("" when missing), and its lines without their ends.
std::string Slurp(const std::string& path);
std::vector<std::string> Lines(const std::string& path);

// Width and height from a PNG's IHDR chunk; {0, 0} if the file is not a PNG.
std::pair<int, int> PngSize(const std::string& path);

// Runs a shell command; returns its exit status and puts stdout+stderr into *output.
int RunCommand(const std::string& command, std::string* output);

// Path of the built rgbdvo executable, of its test build (the same with the tests' own flags,
// apps/debug_flags.hpp) and of the source tree.
std::string RgbdvoExe();
std::string RgbdvoDebugExe();
std::string SourceDir();

}  // namespace rgbdvo::test
