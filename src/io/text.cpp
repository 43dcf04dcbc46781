#include "rgbdvo/io/text.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/util/display_text.hpp"
#include "rgbdvo/util/input_file.hpp"

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
    throw std::runtime_error(where + ": '" + Excerpt(t) + "' is not a number");
  if (errno == ERANGE || !std::isfinite(x))
    throw std::runtime_error(where + ": '" + Excerpt(t) + "' is not finite");
  return x;
}

std::vector<ListLine> ReadListLines(const std::string& path, const std::string& what) {
  std::istringstream in(ReadTextFile(path, what, kMaxListFileBytes));
  std::vector<ListLine> lines;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    lines.push_back({number, line});
  }
  return lines;
}

}  // namespace rgbdvo
