#include "run_common.hpp"

#include <iostream>
#include <opencv2/core/utility.hpp>
#include <sstream>

namespace rgbdvo::cli {

void TrajectoryOutputs::AddFlags(CLI::App* cmd) {
  cmd->add_option("--out", csv, "trajectory CSV, written frame by frame");
  cmd->add_option("--tum", tum, "trajectory in TUM format (timestamp tx ty tz qx qy qz qw)");
}

std::vector<std::unique_ptr<TrajectoryWriter>> TrajectoryOutputs::Open() const {
  std::vector<std::unique_ptr<TrajectoryWriter>> writers;
  if (!csv.empty()) writers.push_back(std::make_unique<CsvTrajectoryWriter>(csv));
  if (!tum.empty()) writers.push_back(std::make_unique<TumTrajectoryWriter>(tum));
  return writers;
}

void AddThreadsFlag(CLI::App* cmd, RunOptions* options) {
  cmd->add_option("--threads", options->threads,
                  "1 = everything on one core (OpenCV's loops too); N >= 2 = N feature workers "
                  "(decode + SIFT) while the main thread matches, estimates and writes in frame "
                  "order (same results); 0 = automatic: the hardware concurrency, at most " +
                      std::to_string(RunOptions::kMaxAutoThreads))
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

void LimitOpenCvThreads() {
  // One thread: one core. N feature workers already keep every core busy, so OpenCV's own
  // parallel loops (cvtColor and the like, inside each worker) would only add threads that
  // compete with them (fr1_xyz, 2 workers, 3 alternating runs each: 33.6 -> 34.1 fps).
  cv::setNumThreads(1);
}

std::function<void(const std::string&)> PrintWarning(bool progress) {
  return [progress](const std::string& warning) {
    std::cerr << (progress ? "\n" : "") << "rgbdvo: warning: " << warning << std::endl;
  };
}

void PrintConfiguration(std::ostream& out, const std::string& source, const std::string& calib_path,
                        const Calibration& calib, const OdometryOptions& options,
                        const RunOptions& run) {
  out << "# rgbdvo " RGBDVO_VERSION "\n# source: " << source << "\n# calibration: " << calib_path
      << " A=" << calib.A << " B=" << calib.B << " C=" << calib.C << " D=" << calib.D
      << " fx=" << calib.fx << " fy=" << calib.fy << " cx=" << calib.cx << " cy=" << calib.cy
      << " depth=[" << calib.min_depth_m << "," << calib.max_depth_m
      << "] m\n# threads: " << run.Describe() << "\n";
  std::istringstream config(options.ToString());
  for (std::string line; std::getline(config, line);) out << "# " << line << "\n";
}

}  // namespace rgbdvo::cli
