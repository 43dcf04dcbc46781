#pragma once
// The subcommands of the `rgbdvo` CLI. Each lives in its own cmd_*.cpp, parses its flags with
// CLI11 and calls one library function; an exception becomes one line on stderr and exit 1.

#include <CLI/CLI.hpp>

#include "rgbdvo/odometry.hpp"

namespace rgbdvo::cli {

// Adds the flags of every OdometryOptions field (paper defaults) to `cmd`.
void AddOdometryFlags(CLI::App* cmd, OdometryOptions* options);

void AddRunCommand(CLI::App& app);

}  // namespace rgbdvo::cli
