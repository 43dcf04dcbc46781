#pragma once
// Every parameter of OdometryOptions, declared once: its key (in the printed configuration and
// in configuration files), its command-line flag and its help. The configuration printout
// (OdometryOptions::ToString), configuration files (--config, --dump-config) and the CLI flags
// are all made from this one list, so they cannot disagree. The run's own options (threads) are
// declared the same way (pipeline/run_parameters.hpp).

#include <cmath>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo {

// Where a parameter lives in its options struct. An enum's values are written by name
// (EnumNames in odometry_parameters.cpp).
using ParameterRef = std::variant<bool*, int*, uint32_t*, double*, SiftImplementation*,
                                  MotionModelKind*, FloorSource*>;

// The values a number parameter may take, both ends included: what a real camera and machine
// could use, so that no value sizes memory or time beyond them (OptionsStruct::Check() keeps the
// rules between fields and the strict bounds, such as "> 0").
struct ParameterRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool Bounded() const { return std::isfinite(min) && std::isfinite(max); }
};

// The value at `field` as configuration text (true/false for booleans).
std::string FormatParameter(ParameterRef field);
// "[3, 101]": the range as the errors and --help show it.
std::string FormatRange(const ParameterRange& range);
// Parses `text` into `field`. Throws std::invalid_argument naming `key` and the text when it is
// not a value of the field's type (booleans: true/false/1/0/yes/no/on/off) or, for a number,
// outside `range`.
void ParseParameter(const char* key, const std::string& text, ParameterRef field,
                    const ParameterRange& range = {});

template <typename Options>
struct Parameter {
  const char* key;   // "matching.ratio": the field's path in Options
  const char* flag;  // "ratio": --ratio VALUE; a boolean has --NAME and --no-NAME
  const char* help;
  ParameterRef (*field)(Options&);
  ParameterRange range = {};  // every number parameter has one (a test checks)

  bool IsBool() const {
    Options o;
    return std::holds_alternative<bool*>(field(o));
  }
  bool IsNumber() const {
    Options o;
    const ParameterRef f = field(o);
    return std::holds_alternative<int*>(f) || std::holds_alternative<uint32_t*>(f) ||
           std::holds_alternative<double*>(f);
  }
  // The value in `options` as configuration text.
  std::string Get(const Options& options) const {
    // `field` only names the member; nothing is written through it here.
    return FormatParameter(field(const_cast<Options&>(options)));
  }
  void Set(const std::string& text, Options* options) const {
    ParseParameter(key, text, field(*options), range);
  }
};
using OdometryParameter = Parameter<OdometryOptions>;

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
// `other` (may be empty) is asked first for each key and value: it returns true when the key is
// its own (another table's, pipeline/run_parameters.hpp) and it has applied the value.
void ApplyConfig(
    std::istream& in, const std::string& name, OdometryOptions* options,
    const std::function<bool(const std::string& key, const std::string& value)>& other = {});
// The same from a file; throws std::runtime_error naming it when it cannot be read.
void ApplyConfigFile(
    const std::string& path, OdometryOptions* options,
    const std::function<bool(const std::string& key, const std::string& value)>& other = {});

}  // namespace rgbdvo
