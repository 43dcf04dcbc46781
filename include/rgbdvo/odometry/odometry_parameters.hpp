#pragma once
// Every parameter of OdometryOptions, declared once: its key (in the printed configuration and
// in configuration files), its command-line flag and its help. The configuration printout
// (OdometryOptions::ToString), configuration files (--config, --dump-config) and the CLI flags
// are all made from this one list, so they cannot disagree.

#include <cstdint>
#include <iosfwd>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo {

// Where a parameter lives in an OdometryOptions. An enum's values are written by name
// (EnumNames in odometry_parameters.cpp).
using ParameterRef = std::variant<bool*, int*, uint32_t*, double*, SiftImplementation*,
                                  MotionModelKind*, FloorSource*>;

struct OdometryParameter {
  const char* key;   // "matching.ratio": the field's path in OdometryOptions
  const char* flag;  // "ratio": --ratio VALUE; a boolean has --NAME and --no-NAME
  const char* help;
  ParameterRef (*field)(OdometryOptions&);

  bool IsBool() const;
  // The value in `options` as configuration text (true/false for booleans).
  std::string Get(const OdometryOptions& options) const;
  // Parses `text` into `options`. Throws std::invalid_argument naming the key and the text when
  // it is not a value of the parameter's type (booleans: true/false/1/0/yes/no/on/off).
  void Set(const std::string& text, OdometryOptions* options) const;
};

// The names an enum parameter is written with, in its enumerators' order.
template <typename E>
const std::vector<std::pair<E, const char*>>& EnumNames();

// All parameters, in the order of the printed configuration.
const std::vector<OdometryParameter>& OdometryParameters();

// The parameter with this key, or nullptr.
const OdometryParameter* FindParameter(const std::string& key);

// A configuration file: one "key = value" a line, keys as OdometryParameters() names them;
// '#' starts a comment, blank lines are ignored (so ToString()'s output is one). Keys of earlier
// versions are read too: renamed ones under their new name, removed ones at their old default
// (a file they set otherwise is refused, with the reason). Each value
// overrides `options`' in file order. Throws std::runtime_error naming `name` and the line for an
// unknown key, a line without '=', or a bad value; the file as a whole is checked afterwards by
// OdometryOptions::Check().
void ApplyConfig(std::istream& in, const std::string& name, OdometryOptions* options);
// The same from a file; throws std::runtime_error naming it when it cannot be read.
void ApplyConfigFile(const std::string& path, OdometryOptions* options);

}  // namespace rgbdvo
