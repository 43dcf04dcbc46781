#pragma once
// The odometry flags shared by `run` and `capture`: a --preset and one flag per parameter.
// Flags given on the command line override the preset's values.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo::cli {

class OdometryFlags {
 public:
  explicit OdometryFlags(CLI::App* cmd);
  // The preset's options with every flag the user gave applied on top; checked.
  OdometryOptions Resolve() const;

 private:
  template <typename T>
  void Add(const std::string& name, T& (*field)(OdometryOptions&), const std::string& help);
  void AddSwitch(const std::string& name, bool& (*field)(OdometryOptions&), bool value,
                 const std::string& help);

  CLI::App* cmd_;
  std::string preset_ = "default";
  OdometryOptions given_;
  std::vector<std::function<void(OdometryOptions&)>> apply_given_;
};

}  // namespace rgbdvo::cli
