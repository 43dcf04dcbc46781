#pragma once
// The configuration flags shared by `run` and `capture`, made from the two lists of parameters
// (odometry/odometry_parameters.hpp, pipeline/run_parameters.hpp): --preset, --config FILE,
// --dump-config, and a flag per parameter (--NAME VALUE; booleans --NAME / --no-NAME). Applied
// in that order: the preset (and the command's run defaults), then the file, then the flags
// given on the command line.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/pipeline/run.hpp"

namespace rgbdvo::cli {

struct Configuration {
  OdometryOptions odometry;
  RunOptions run;
};

class ConfigurationFlags {
 public:
  // `run_defaults`: the command's own (capture reads fewer frames ahead than run).
  ConfigurationFlags(CLI::App* cmd, const RunOptions& run_defaults);
  // The preset's options, the configuration file's values and every flag the user gave on top;
  // checked.
  Configuration Resolve() const;
  // --dump-config was given: the command prints DumpConfig() and exits.
  bool dump_requested() const { return dump_; }
  // Resolve() as a configuration file (what --config reads), with a header naming its sources.
  std::string DumpConfig() const;
  // --config's file, or empty: an input no output may overwrite.
  const std::string& config_path() const { return config_; }

  struct Given {
    std::string text;            // the value of --NAME VALUE
    CLI::Option* on = nullptr;   // --NAME (a value option, or a boolean's positive form)
    CLI::Option* off = nullptr;  // --no-NAME (booleans)
  };

 private:
  std::string preset_ = "default";
  std::string config_;
  bool dump_ = false;
  RunOptions run_defaults_;
  // One per OdometryParameters() entry, then one per RunParameters() entry.
  std::vector<std::unique_ptr<Given>> given_;
};

}  // namespace rgbdvo::cli
