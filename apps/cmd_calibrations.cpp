// `rgbdvo calibrations`: the calibration files --calib finds by name; and that --calib flag.
#include <iostream>

#include "commands.hpp"
#include "rgbdvo/sensor/calibration_catalog.hpp"

namespace rgbdvo::cli {

CLI::Option* AddCalibFlag(CLI::App* cmd, std::string* path, const std::string& help) {
  // Resolved by the command (FindCalibration) after parsing: a bad command line is reported as
  // such before a missing file.
  return cmd->add_option(
      "--calib", *path,
      help + ": a file, or a name that `rgbdvo calibrations` lists (e.g. tum_fr1)");
}

void AddCalibrationsCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "calibrations", "list the calibration files that --calib finds by name, and where");
  auto verbose = std::make_shared<bool>(false);
  cmd->add_flag("--verbose", *verbose, "also print each file's description");
  cmd->callback([verbose] {
    const std::vector<CalibrationEntry> entries = ListCalibrations();
    if (entries.empty())
      std::cerr << "rgbdvo: no calibration files found (searched: RGBDVO_CALIB_PATH, "
                   "share/rgbdvo/calib)\n";
    for (const CalibrationEntry& e : entries) {
      std::cout << e.name << "\t" << e.path << "\n";
      if (*verbose && !e.description.empty()) std::cout << "\t" << e.description << "\n";
    }
    std::cout << std::flush;
  });
}

}  // namespace rgbdvo::cli
