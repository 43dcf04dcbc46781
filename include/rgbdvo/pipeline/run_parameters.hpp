#pragma once
// RunOptions' parameters, declared as OdometryOptions' are (odometry/odometry_parameters.hpp):
// keys under "run." in configuration files and the printed configuration, and their flags.

#include <iosfwd>
#include <string>
#include <vector>

#include "rgbdvo/odometry/odometry_parameters.hpp"
#include "rgbdvo/pipeline/run.hpp"

namespace rgbdvo {

using RunParameter = Parameter<RunOptions>;

// All of RunOptions' parameters, in the order of the printed configuration.
const std::vector<RunParameter>& RunParameters();

// The parameter with this key ("run.threads"), or nullptr.
const RunParameter* FindRunParameter(const std::string& key);

// The whole configuration as a configuration file: the odometry's keys, then the run's.
std::string ConfigurationText(const OdometryOptions& odometry, const RunOptions& run);

// A configuration file of both tables' keys (ApplyConfig's rules): "run." keys set `run`, the
// others `odometry`. Throws std::runtime_error naming the file (and line).
void ApplyConfig(std::istream& in, const std::string& name, OdometryOptions* odometry,
                 RunOptions* run);
void ApplyConfigFile(const std::string& path, OdometryOptions* odometry, RunOptions* run);

}  // namespace rgbdvo
