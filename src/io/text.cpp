#include "rgbdvo/io/text.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace rgbdvo {

std::string Trim(const std::string& s) {
  constexpr const char* kSpace = " \t\r\n";
  const size_t b = s.find_first_not_of(kSpace);
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(kSpace) - b + 1);
}

double ParseNumber(const std::string& field, const std::string& where) {
  const std::string t = Trim(field);
  const char* begin = t.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  if (t.empty() || end != begin + t.size())
    throw std::runtime_error(where + ": '" + t + "' is not a number");
  if (errno == ERANGE || !std::isfinite(x))
    throw std::runtime_error(where + ": '" + t + "' is not finite");
  return x;
}

}  // namespace rgbdvo
