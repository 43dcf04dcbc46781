#pragma once
// Benchmark-only runners for peer RGB-D odometries (OpenCV cv::rgbd, Open3D). They read a TUM
// folder through rgbdvo's own TumSource, so every method sees the same frames, run frame to
// frame (each frame against the previous one) and write a camera-to-world TUM trajectory.
// Not part of the library: only bench/ links the peer libraries (BUILD_BENCH_PEERS).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame.hpp"

namespace rgbdvo::bench {

// One peer method, fed frames in order.
class PeerOdometry {
 public:
  virtual ~PeerOdometry() = default;
  // Feeds the next frame. For every frame but the first, sets prev_from_cur (p_prev =
  // prev_from_cur * p_cur) and returns false when the method reports failure.
  virtual bool Track(const Frame& cur, Rigid3d* prev_from_cur) = 0;
  // One line: the method and its effective settings.
  virtual std::string Describe() const = 0;
};

using PeerFactory =
    std::function<std::unique_ptr<PeerOdometry>(const std::string& method, const Calibration&)>;

// main() of a peer runner: `NAME FOLDER --calib FILE --method M --tum OUT.txt`. Prints the
// configuration (`#` lines), `failures=K of P` and last `frames=N fps=F`, where fps counts the
// whole loop (decode + odometry + writing). Returns the process exit code.
int RunPeerMain(int argc, char** argv, const std::string& name,
                const std::vector<std::string>& methods, const PeerFactory& factory);

// The rotation of a 4x4 matrix projected onto SO(3), with its translation.
Rigid3d RigidFromMatrix(const Eigen::Matrix4d& M);

}  // namespace rgbdvo::bench
