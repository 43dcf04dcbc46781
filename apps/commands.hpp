#pragma once
// The subcommands of the `rgbdvo` CLI. Each lives in its own cmd_*.cpp, parses its flags with
// CLI11 and calls one library function; an exception becomes one line on stderr and exit 1.

#include <CLI/CLI.hpp>
#include <string>

#include "configuration_flags.hpp"

namespace rgbdvo::cli {

void AddRunCommand(CLI::App& app);
void AddCalibrateCommand(CLI::App& app);
void AddEvalCommand(CLI::App& app);
void AddPlotCommand(CLI::App& app);
void AddCaptureCommand(CLI::App& app);
void AddSynthKinectCommand(CLI::App& app);
void AddCalibrationsCommand(CLI::App& app);
void AddInfoCommand(CLI::App& app);

// --calib: a calibration file or the name of one (FindCalibration gives the file).
CLI::Option* AddCalibFlag(CLI::App* cmd, std::string* path, const std::string& help);

}  // namespace rgbdvo::cli
