#include "rgbdvo/calibrate/pixel_pairs_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/io/text.hpp"
#include "rgbdvo/util/display_text.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

constexpr const char* kHeader = "u_vis,v_vis,u_ir,v_ir";
constexpr const char* kHeaderWithDepth = "u_vis,v_vis,u_ir,v_ir,z_ir_m";

}  // namespace

std::vector<PixelPair> LoadPixelPairs(const std::string& path) {
  std::istringstream in(ReadTextFile(path, "pairs file", kMaxListFileBytes));
  std::vector<PixelPair> pairs;
  bool header_seen = false;
  size_t columns = 4;
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const std::string where = path + ":" + std::to_string(line_no);
    line = Trim(line);
    if (line.empty() || line[0] == '#') continue;
    if (!header_seen) {
      std::string compact;
      for (char c : line)
        if (c != ' ' && c != '\t') compact += c;
      if (compact != kHeader && compact != kHeaderWithDepth)
        throw std::runtime_error(where + ": expected the header '" + kHeader + "' or '" +
                                 kHeaderWithDepth + "', got '" + Excerpt(line) + "'");
      columns = compact == kHeader ? 4 : 5;
      header_seen = true;
      continue;
    }
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    if (line.back() == ',') fields.push_back("");
    if (fields.size() != columns)
      throw std::runtime_error(where + ": expected " + std::to_string(columns) +
                               " comma-separated numbers (" +
                               (columns == 4 ? kHeader : kHeaderWithDepth) + "), got " +
                               std::to_string(fields.size()) + " fields");
    PixelPair p;
    p.u_vis = ParseNumber(fields[0], where);
    p.v_vis = ParseNumber(fields[1], where);
    p.u_ir = ParseNumber(fields[2], where);
    p.v_ir = ParseNumber(fields[3], where);
    if (columns == 5) {
      p.z_ir_m = ParseNumber(fields[4], where);
      if (!(p.z_ir_m >= 0)) throw std::runtime_error(where + ": z_ir_m must be >= 0 (0: unknown)");
    }
    pairs.push_back(p);
  }
  if (!header_seen)
    throw std::runtime_error(path + ": empty pairs file (no '" + kHeader + "' header)");
  return pairs;
}

void SavePixelPairs(const std::vector<PixelPair>& pairs, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write pairs file");
  out.precision(10);
  bool depths = false;
  for (const PixelPair& p : pairs) depths = depths || p.z_ir_m > 0;
  out << (depths ? kHeaderWithDepth : kHeader) << "\n";
  for (const PixelPair& p : pairs) {
    out << p.u_vis << "," << p.v_vis << "," << p.u_ir << "," << p.v_ir;
    if (depths) out << "," << p.z_ir_m;
    out << "\n";
  }
  out.flush();
  if (!out) throw std::runtime_error(path + ": error while writing pairs file");
}

}  // namespace rgbdvo
