#pragma once
// The odometry flags shared by `run` and `capture`, made from the one list of parameters
// (odometry/odometry_parameters.hpp): --preset, --config FILE, --dump-config, and a flag per
// parameter (--NAME VALUE; booleans --NAME / --no-NAME). Applied in that order: the preset,
// then the file, then the flags given on the command line.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo::cli {

class OdometryFlags {
 public:
  explicit OdometryFlags(CLI::App* cmd);
  // The preset's options, the configuration file's values and every flag the user gave on top;
  // checked.
  OdometryOptions Resolve() const;
  // --dump-config was given: the command prints DumpConfig() and exits.
  bool dump_requested() const { return dump_; }
  // Resolve() as a configuration file (what --config reads), with a header naming its sources.
  std::string DumpConfig() const;

 private:
  struct Given {
    std::string text;            // the value of --NAME VALUE
    CLI::Option* on = nullptr;   // --NAME (a value option, or a boolean's positive form)
    CLI::Option* off = nullptr;  // --no-NAME (booleans)
  };
  std::string preset_ = "default";
  std::string config_;
  bool dump_ = false;
  std::vector<std::unique_ptr<Given>> given_;  // one per OdometryParameters() entry
};

}  // namespace rgbdvo::cli
