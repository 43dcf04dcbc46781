#include "run_common.hpp"

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

void PrintConfiguration(std::ostream& out, const std::string& source, const std::string& calib_path,
                        const Calibration& calib, const OdometryOptions& options) {
  out << "# source: " << source << "\n# calibration: " << calib_path << " A=" << calib.A
      << " B=" << calib.B << " C=" << calib.C << " D=" << calib.D << " fx=" << calib.fx
      << " fy=" << calib.fy << " cx=" << calib.cx << " cy=" << calib.cy << " depth=["
      << calib.min_depth_m << "," << calib.max_depth_m << "] m\n";
  std::istringstream config(options.ToString());
  for (std::string line; std::getline(config, line);) out << "# " << line << "\n";
}

}  // namespace rgbdvo::cli
