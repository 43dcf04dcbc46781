#pragma once
// What `run` and `capture` share: the trajectory output flags, --threads and the configuration
// header.

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "rgbdvo/calibration.hpp"
#include "rgbdvo/odometry.hpp"
#include "rgbdvo/run.hpp"
#include "rgbdvo/trajectory_writer.hpp"

namespace rgbdvo::cli {

struct TrajectoryOutputs {
  std::string csv, tum;
  void AddFlags(CLI::App* cmd);  // --out, --tum
  // A writer per file given; throws naming a file that cannot be written.
  std::vector<std::unique_ptr<TrajectoryWriter>> Open() const;
};

// --threads into options->threads.
void AddThreadsFlag(CLI::App* cmd, RunOptions* options);
// Turns OpenCV's own parallel loops off: our threads (one, or the feature workers) are the
// parallelism.
void LimitOpenCvThreads();

// A run's on_warning: "rgbdvo: warning: ..." on stderr, on a fresh line when a progress line
// (`progress`) is being redrawn there.
std::function<void(const std::string&)> PrintWarning(bool progress);

// The effective configuration as `# ` lines, so a run can be reproduced.
void PrintConfiguration(std::ostream& out, const std::string& source, const std::string& calib_path,
                        const Calibration& calib, const OdometryOptions& options,
                        const RunOptions& run);

}  // namespace rgbdvo::cli
