#include "rgbdvo/sources/association_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/io/text.hpp"
#include "rgbdvo/util/display_text.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

// The pair on a line, or false when the line is not `t path t path`.
bool ParseAssociation(const std::string& line, TumPair* pair) {
  std::istringstream fields(line);
  std::string rest;
  return fields >> pair->rgb.timestamp >> pair->rgb.path >> pair->depth.timestamp >>
             pair->depth.path &&
         !(fields >> rest) && std::isfinite(pair->rgb.timestamp) &&
         std::isfinite(pair->depth.timestamp);
}

bool IsContent(const std::string& line) {
  const size_t first = line.find_first_not_of(" \t\r");
  return first != std::string::npos && line[first] != '#';
}

}  // namespace

std::vector<TumPair> ReadAssociations(const std::string& path) {
  std::vector<TumPair> pairs;
  for (const ListLine& line : ReadListLines(path, "association file")) {
    TumPair pair;
    if (!ParseAssociation(line.text, &pair))
      throw std::runtime_error(path + ":" + std::to_string(line.number) +
                               ": expected 't_rgb rgb_path t_depth depth_path', got '" +
                               Excerpt(line.text) + "'");
    pairs.push_back(pair);
  }
  if (pairs.empty()) throw std::runtime_error(path + ": empty association file (no pair)");
  return pairs;
}

bool IsAssociationFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) return false;
  std::ifstream in(path);
  std::string line;
  for (int n = 0; n < 1000 && std::getline(in, line); ++n) {
    if (line.size() > 4096) return false;
    if (n == 0) line = WithoutByteOrderMark(line);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!IsContent(line)) continue;
    TumPair pair;
    return ParseAssociation(line, &pair);
  }
  return false;
}

}  // namespace rgbdvo
