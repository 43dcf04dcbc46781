#include "peer_runner.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/sources/tum_source.hpp"
#include "rgbdvo/util/stopwatch.hpp"

namespace rgbdvo::bench {
namespace {

struct PeerArgs {
  std::string folder, calib, method, tum;
};

void WriteTumRow(std::ofstream& out, const std::string& path, double timestamp,
                 const Rigid3d& world_from_cam) {
  rgbdvo::WriteTumLine(out, timestamp, world_from_cam);
  out.flush();
  if (!out) throw std::runtime_error(path + ": write failed");
}

int Run(const std::string& name, const PeerArgs& a, const PeerFactory& factory) {
  const Calibration calib = LoadCalibration(a.calib);
  if (calib.A != 1 || calib.B != 0 || calib.C != 1 || calib.D != 0) {
    throw std::runtime_error(a.calib + ": peers need registered depth (A=1, B=0, C=1, D=0)");
  }
  TumSource source(a.folder, TumSourceOptions{});
  std::unique_ptr<PeerOdometry> peer = factory(a.method, calib);
  std::ofstream out(a.tum, std::ios::out | std::ios::trunc);
  if (!out) throw std::runtime_error(a.tum + ": cannot open for writing");
  out << "# timestamp tx ty tz qx qy qz qw (camera-to-world, " << name << " " << a.method << ")\n";

  std::cout << "# source: " << source.Describe() << "\n# calibration: " << a.calib
            << " fx=" << calib.fx << " fy=" << calib.fy << " cx=" << calib.cx << " cy=" << calib.cy
            << " (pinhole: the peers take no lens distortion"
            << (calib.dist_ir == decltype(calib.dist_ir){} ? "" : "; dist_ir ignored") << ")"
            << "\n# method: " << peer->Describe() << std::endl;

  const rgbdvo::Stopwatch start;
  Rigid3d world_from_cam = Rigid3d::Identity();
  int frames = 0, failures = 0;
  while (std::optional<Frame> frame = source.Next()) {
    Rigid3d prev_from_cur = Rigid3d::Identity();
    const bool ok = peer->Track(*frame, &prev_from_cur);
    if (frames > 0) {
      if (ok) {
        world_from_cam = world_from_cam * prev_from_cur;
      } else {
        ++failures;  // identity motion: keep the previous pose
      }
    }
    WriteTumRow(out, a.tum, frame->timestamp, world_from_cam);
    ++frames;
  }
  const double seconds = start.Seconds();
  std::cout << "failures=" << failures << " of " << std::max(frames - 1, 0) << " pairs\n";
  std::cout << "frames=" << frames << " fps=" << std::setprecision(3) << std::fixed
            << (seconds > 0 ? frames / seconds : 0.0) << std::endl;
  return 0;
}

}  // namespace

int RunPeerMain(int argc, char** argv, const std::string& name,
                const std::vector<std::string>& methods, const PeerFactory& factory) {
  CLI::App app{name + ": frame-to-frame peer odometry over a TUM folder (benchmark only)"};
  PeerArgs a;
  app.add_option("folder", a.folder, "TUM RGB-D folder")->required();
  app.add_option("--calib", a.calib, "rgbdvo calibration YAML (registered depth)")->required();
  app.add_option("--method", a.method, "odometry method")
      ->required()
      ->check(CLI::IsMember(methods));
  app.add_option("--tum", a.tum, "output trajectory, TUM format, camera-to-world")->required();
  try {
    app.parse(argc, argv);
    return Run(name, a, factory);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << name << ": error: " << e.what() << std::endl;
    return 1;
  }
}

Rigid3d RigidFromMatrix(const Eigen::Matrix4d& M) {
  Rigid3d T = Rigid3d::Identity();
  T.linear() = NearestRotation(M.topLeftCorner<3, 3>());
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

}  // namespace rgbdvo::bench
