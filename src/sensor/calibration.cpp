#include "rgbdvo/sensor/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rgbdvo/util/display_text.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("calibration: " + what);
}

// The calibration file's YAML, read by its own small reader: the top-level "key: value" lines
// and "key: !!opencv-matrix" blocks (rows, cols, dt, data: [ ... ] over one or more lines) that
// SaveCalibration (OpenCV's writer) produces and a user edits. OpenCV's own YAML reader loops
// forever on some malformed files (two found by tests/fuzz) and recurses without limit on
// nesting; this one reads each line once and nests two levels at most.
struct YamlNode {
  int line = 0;                    // where it was defined, for messages
  std::string scalar;              // a value (quotes removed)
  bool quoted = false;             // the value was a "string"
  std::vector<std::string> items;  // a [ ... ] list
  bool is_list = false;
  std::map<std::string, YamlNode> children;  // a block of indented "key: value" lines
  bool is_map = false;
};

class CalibrationYaml {
 public:
  CalibrationYaml(const std::string& text, const std::string& path) : path_(path) {
    std::istringstream in(text);
    std::string raw;
    YamlNode* block = nullptr;  // the top-level node whose indented lines follow
    YamlNode* list = nullptr;   // an open [ ... ] continuing on the next lines
    while (std::getline(in, raw)) {
      ++line_;
      const std::string content = StripComment(raw);
      if (list) {
        list_text_ += " " + content;
        if (content.find(']') != std::string::npos) CloseList(list), list = nullptr;
        continue;
      }
      const size_t indent = content.find_first_not_of(" \t");
      if (indent == std::string::npos) continue;  // blank or comment only
      if (line_ == 1 && content.rfind("%YAML", 0) == 0) continue;
      if (content == "---") continue;
      const size_t colon = content.find(':');
      if (colon == std::string::npos) throw Error("expected 'key: value'");
      const std::string key = Trim(content.substr(indent, colon - indent));
      const std::string value = Trim(content.substr(colon + 1));
      if (key.empty() || key.find_first_of(" \t\"'[]{}") != std::string::npos)
        throw Error("bad key '" + Excerpt(key) + "'");
      std::map<std::string, YamlNode>* into = &top_;
      if (indent > 0) {
        if (!block) throw Error("indented line outside a matrix block");
        into = &block->children;
      } else {
        block = nullptr;
      }
      if (into->count(key)) throw Error("'" + Excerpt(key) + "' given twice");
      YamlNode& node = (*into)[key];
      node.line = line_;
      if (value.rfind('[', 0) == 0) {
        node.is_list = true;
        list_text_ = value.substr(1);
        if (value.find(']') != std::string::npos)
          CloseList(&node);
        else
          list = &node;
      } else if (indent == 0 && (value.empty() || value.rfind("!!", 0) == 0)) {
        node.is_map = true;
        block = &node;
      } else {
        ParseScalar(value, &node);
      }
    }
    if (list) throw Error("unterminated '[' list (no ']')");
  }

  const YamlNode* Find(const std::string& key) const {
    const auto it = top_.find(key);
    return it == top_.end() ? nullptr : &it->second;
  }
  const std::map<std::string, YamlNode>& top() const { return top_; }

 private:
  std::runtime_error Error(const std::string& what) const {
    return std::runtime_error(path_ + ":" + std::to_string(line_) +
                              ": not a calibration YAML file (" + what + ")");
  }

  // The line without a '#' comment (a '#' inside "quotes" is text) and without a trailing CR.
  static std::string StripComment(const std::string& raw) {
    bool in_quotes = false;
    for (size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '\\' && in_quotes)
        ++i;
      else if (raw[i] == '"')
        in_quotes = !in_quotes;
      else if (raw[i] == '#' && !in_quotes && (i == 0 || raw[i - 1] == ' ' || raw[i - 1] == '\t'))
        return raw.substr(0, i);
    }
    std::string s = raw;
    if (!s.empty() && s.back() == '\r') s.pop_back();
    return s;
  }

  void ParseScalar(const std::string& value, YamlNode* node) const {
    if (value.empty() || value[0] != '"') {
      if (value.find_first_of("[]{}\"") != std::string::npos)
        throw Error("bad value '" + Excerpt(value) + "'");
      node->scalar = value;
      return;
    }
    node->quoted = true;
    size_t i = 1;
    for (; i < value.size() && value[i] != '"'; ++i) {
      if (value[i] == '\\' && i + 1 < value.size()) ++i;
      node->scalar += value[i];
    }
    if (i >= value.size() || Trim(value.substr(i + 1)) != "") throw Error("bad quoted string");
  }

  void CloseList(YamlNode* node) {
    const size_t close = list_text_.find(']');
    if (Trim(list_text_.substr(close + 1)) != "") throw Error("text after ']'");
    std::istringstream items(list_text_.substr(0, close));
    for (std::string item; std::getline(items, item, ',');) {
      item = Trim(item);
      if (item.empty() || item.find_first_of("[{") != std::string::npos)
        throw Error("bad list item '" + Excerpt(item) + "'");
      node->items.push_back(item);
    }
    list_text_.clear();
  }

  static std::string Trim(const std::string& s) {
    const size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? "" : s.substr(b, e - b + 1);
  }

  std::string path_;
  int line_ = 0;
  std::string list_text_;
  std::map<std::string, YamlNode> top_;
};

// The number a scalar holds (the whole text, finite or not: Check() judges the value), else
// nullopt.
std::optional<double> Number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return v;
}

double ReadNumber(const CalibrationYaml& yaml, const std::string& key, const std::string& path) {
  const YamlNode* node = yaml.Find(key);
  std::optional<double> v;
  if (node && !node->quoted && !node->is_map && !node->is_list) v = Number(node->scalar);
  if (!v) throw std::runtime_error(path + ": missing or non-numeric field '" + key + "'");
  return *v;
}

// The values of an opencv-matrix field (rows, cols, data), row-major, after its shape is checked
// against the expected one (a 1x5 field may be written 5x1).
std::vector<double> ReadMatrix(const YamlNode& node, const std::string& key, int rows, int cols,
                               const std::string& path) {
  const std::string shape = std::to_string(rows) + "x" + std::to_string(cols);
  const auto fail = [&](const std::string& why) {
    return std::runtime_error(path + ": field '" + key + "' must be a " + shape +
                              " opencv-matrix (" + why + ")");
  };
  if (!node.is_map) throw fail("not a matrix");
  const auto integer = [&](const char* name) -> std::optional<double> {
    const auto it = node.children.find(name);
    if (it == node.children.end() || it->second.quoted) return std::nullopt;
    const std::optional<double> v = Number(it->second.scalar);
    if (!v || *v != std::floor(*v) || std::abs(*v) > 9e15) return std::nullopt;
    return v;
  };
  const std::optional<double> r = integer("rows"), c = integer("cols");
  if (!r || !c) throw fail("rows or cols missing");
  if (*r * *c != double(rows) * cols || (*r != rows && *r != cols))
    throw fail("it is " + std::to_string(int64_t(*r)) + "x" + std::to_string(int64_t(*c)));
  const auto data = node.children.find("data");
  if (data == node.children.end() || !data->second.is_list ||
      data->second.items.size() != static_cast<size_t>(rows) * cols)
    throw fail("data must hold " + std::to_string(rows * cols) + " numbers");
  std::vector<double> values;
  for (const std::string& item : data->second.items) {
    const std::optional<double> v = Number(item);
    if (!v) throw fail("data must be numbers");
    values.push_back(*v);
  }
  return values;
}

// The calibration file's own fields (SaveCalibration's layout).
Calibration FromCalibrationFields(const CalibrationYaml& yaml, const std::string& path) {
  Calibration c;
  c.A = ReadNumber(yaml, "A", path);
  c.B = ReadNumber(yaml, "B", path);
  c.C = ReadNumber(yaml, "C", path);
  c.D = ReadNumber(yaml, "D", path);
  if (yaml.Find("s_u")) c.s_u = ReadNumber(yaml, "s_u", path);
  if (yaml.Find("s_v")) c.s_v = ReadNumber(yaml, "s_v", path);
  const YamlNode* k_node = yaml.Find("K_ir");
  if (!k_node) throw std::runtime_error(path + ": missing field 'K_ir'");
  const std::vector<double> K = ReadMatrix(*k_node, "K_ir", 3, 3, path);  // row-major
  c.fx = K[0];
  c.fy = K[4];
  c.cx = K[2];
  c.cy = K[5];
  if (const YamlNode* dist_node = yaml.Find("dist_ir")) {
    const std::vector<double> dist = ReadMatrix(*dist_node, "dist_ir", 1, 5, path);  // or 5x1
    std::copy(dist.begin(), dist.end(), c.dist_ir.begin());
  }
  c.min_depth_m = ReadNumber(yaml, "min_depth_m", path);
  c.max_depth_m = ReadNumber(yaml, "max_depth_m", path);
  if (yaml.Find("depth_units_per_m")) {
    c.depth_units_per_m = ReadNumber(yaml, "depth_units_per_m", path);
    if (!(c.depth_units_per_m > 0))
      throw std::runtime_error(path + ": field 'depth_units_per_m' must be > 0");
  }
  if (const YamlNode* d = yaml.Find("description")) c.description = d->scalar;
  return c;
}

// A ROS camera_info YAML file (as camera_calibration and camera_info_manager write it):
// camera_matrix, distortion_model and distortion_coefficients; the depth registered to this
// camera (the identity mapping), the default depth range unless min_depth_m/max_depth_m are
// added.
Calibration FromCameraInfo(const CalibrationYaml& yaml, const std::string& path) {
  // Shape and data that disagree were edited wrong, and which of the two is right is unknown.
  for (const auto& [key, node] : yaml.top()) {
    const auto rows = node.children.find("rows"), cols = node.children.find("cols");
    const auto data = node.children.find("data");
    if (!node.is_map || rows == node.children.end() || cols == node.children.end() ||
        data == node.children.end())
      continue;
    const std::optional<double> r = Number(rows->second.scalar), c = Number(cols->second.scalar);
    if (!r || !c || *r < 0 || *c < 0 || *r != std::floor(*r) || *c != std::floor(*c) ||
        *r * *c != double(data->second.items.size()))
      throw std::runtime_error(path + ":" + std::to_string(node.line) + ": field '" + Excerpt(key) +
                               "' has " + std::to_string(data->second.items.size()) +
                               " values in its data but rows " + Excerpt(rows->second.scalar) +
                               ", cols " + Excerpt(cols->second.scalar));
  }
  Calibration c;
  const std::vector<double> K =
      ReadMatrix(*yaml.Find("camera_matrix"), "camera_matrix", 3, 3, path);
  c.fx = K[0], c.fy = K[4], c.cx = K[2], c.cy = K[5];
  const YamlNode* model = yaml.Find("distortion_model");
  const std::string name = model ? model->scalar : "plumb_bob";
  if (name != "plumb_bob" && name != "rational_polynomial")
    throw std::runtime_error(path + ": distortion_model '" + Excerpt(name) +
                             "' not supported (plumb_bob, rational_polynomial)");
  if (const YamlNode* d = yaml.Find("distortion_coefficients")) {
    const auto data = d->children.find("data");
    if (!d->is_map || data == d->children.end() || !data->second.is_list)
      throw std::runtime_error(path + ": field 'distortion_coefficients' must have a data list");
    const std::vector<std::string>& items = data->second.items;
    for (size_t i = 0; i < std::min<size_t>(5, items.size()); ++i) {
      const std::optional<double> v = Number(items[i]);
      if (!v) throw std::runtime_error(path + ": distortion_coefficients must be numbers");
      c.dist_ir[i] = *v;  // k1 k2 p1 p2 k3: the first five of both models
    }
  }
  if (yaml.Find("min_depth_m")) c.min_depth_m = ReadNumber(yaml, "min_depth_m", path);
  if (yaml.Find("max_depth_m")) c.max_depth_m = ReadNumber(yaml, "max_depth_m", path);
  const YamlNode* camera = yaml.Find("camera_name");
  c.description = "ROS camera_info" + (camera ? " of " + camera->scalar : std::string()) +
                  " (depth registered to it: identity colour->depth mapping)";
  return c;
}

}  // namespace

void Calibration::Check() const {
  for (double v : {A, B, C, D, s_u, s_v, fx, fy, cx, cy, min_depth_m, max_depth_m})
    Require(std::isfinite(v), "all fields must be finite numbers");
  for (double v : dist_ir) Require(std::isfinite(v), "dist_ir values must be finite numbers");
  Require(A != 0.0, "A must be non-zero (u_ir = A*u + B)");
  Require(C != 0.0, "C must be non-zero (v_ir = C*v + D)");
  Require(fx > 0 && fy > 0, "K_ir focal lengths fx, fy must be > 0");
  Require(min_depth_m >= 0, "min_depth_m must be >= 0");
  Require(max_depth_m > min_depth_m, "max_depth_m must be > min_depth_m");
  Require(std::isfinite(depth_units_per_m) && depth_units_per_m >= 0,
          "depth_units_per_m must be > 0 (or 0: not given)");
}

Calibration LoadCalibration(const std::string& path) {
  // A calibration is a page of text; a larger file is not one (and would be parsed whole).
  const std::string text = ReadTextFile(path, "calibration file", kMaxConfigFileBytes);
  // A calibration is text: control bytes are refused before anything else.
  for (size_t i = 0; i < text.size(); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", byte);
      throw std::runtime_error(path + ": not a text file (control byte " + hex + " at offset " +
                               std::to_string(i) + ")");
    }
  }
  const CalibrationYaml yaml(text, path);
  Calibration c;
  if (!yaml.Find("K_ir") && yaml.Find("camera_matrix")) {
    c = FromCameraInfo(yaml, path);
  } else {
    c = FromCalibrationFields(yaml, path);
  }
  try {
    c.Check();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return c;
}

void SaveCalibration(const Calibration& c, const std::string& path) {
  c.Check();
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": cannot write calibration file (" + e.err + ")");
  }
  if (!fs.isOpened()) throw std::runtime_error(path + ": cannot write calibration file");
  if (!c.description.empty()) fs << "description" << c.description;
  fs.writeComment("u_ir = A * u_vis + B, v_ir = C * v_vis + D (Fiala & Ufkes 2011, eq. 1)");
  fs << "A" << c.A << "B" << c.B << "C" << c.C << "D" << c.D;
  if (c.HasDisparityTerm()) {
    fs.writeComment("depth-aware: u_ir += s_u / z, v_ir += s_v / z (z: depth, m; s: px m)");
    fs << "s_u" << c.s_u << "s_v" << c.s_v;
  }
  const cv::Mat K = (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  fs << "K_ir" << K;
  if (c.dist_ir != std::array<double, 5>{0, 0, 0, 0, 0}) {
    fs.writeComment("distortion of the depth camera: k1 k2 p1 p2 k3 (OpenCV model)");
    fs << "dist_ir" << cv::Mat(1, 5, CV_64F, const_cast<double*>(c.dist_ir.data())).clone();
  }
  fs << "min_depth_m" << c.min_depth_m << "max_depth_m" << c.max_depth_m;
  if (c.depth_units_per_m > 0) {
    fs.writeComment("16-bit depth images: units per metre");
    fs << "depth_units_per_m" << c.depth_units_per_m;
  }
}

}  // namespace rgbdvo
