#include "rgbdvo/sensor/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace rgbdvo {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("calibration: " + what);
}

double ReadNumber(const cv::FileStorage& fs, const std::string& key, const std::string& path) {
  const cv::FileNode node = fs[key];
  if (node.empty() || (!node.isReal() && !node.isInt()))
    throw std::runtime_error(path + ": missing or non-numeric field '" + key + "'");
  return static_cast<double>(node);
}

// The values of an opencv-matrix field (rows, cols, dt, data), read one by one after its shape
// is checked against the expected one: OpenCV's own reader allocates rows x cols as the file
// claims before it looks at the data.
std::vector<double> ReadMatrix(const cv::FileStorage& fs, const std::string& key, int rows,
                               int cols, const std::string& path) {
  const std::string shape = std::to_string(rows) + "x" + std::to_string(cols);
  const cv::FileNode node = fs[key];
  const auto fail = [&](const std::string& why) {
    return std::runtime_error(path + ": field '" + key + "' must be a " + shape +
                              " opencv-matrix (" + why + ")");
  };
  if (!node.isMap()) throw fail("not a matrix");
  const cv::FileNode r = node["rows"], c = node["cols"], data = node["data"];
  if (!r.isInt() || !c.isInt()) throw fail("rows or cols missing");
  const int file_rows = static_cast<int>(r), file_cols = static_cast<int>(c);
  if (file_rows * int64_t{file_cols} != int64_t{rows} * cols ||
      (file_rows != rows && file_rows != cols))
    throw fail("it is " + std::to_string(file_rows) + "x" + std::to_string(file_cols));
  if (!data.isSeq() || data.size() != static_cast<size_t>(rows) * cols)
    throw fail("data must hold " + std::to_string(rows * cols) + " numbers");
  std::vector<double> values;
  for (const cv::FileNode& v : data) {
    if (!v.isReal() && !v.isInt()) throw fail("data must be numbers");
    values.push_back(static_cast<double>(v));
  }
  return values;
}

}  // namespace

void Calibration::Check() const {
  for (double v : {A, B, C, D, fx, fy, cx, cy, min_depth_m, max_depth_m})
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
  constexpr std::uintmax_t kMaxBytes = 1 << 20;
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error(path + ": cannot open calibration file (" + ec.message() + ")");
  if (bytes > kMaxBytes)
    throw std::runtime_error(path + ": " + std::to_string(bytes) +
                             " bytes, too large for a calibration file (at most 1 MiB)");
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw std::runtime_error(path + ": cannot read calibration file");
  // A calibration is text. OpenCV's YAML reader loops forever on some inputs with control bytes
  // (a NUL in a 75-byte file, found by tests/fuzz), so they are refused before it sees them.
  for (size_t i = 0; i < text.size(); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", byte);
      throw std::runtime_error(path + ": not a text file (control byte " + hex + " at offset " +
                               std::to_string(i) + ")");
    }
  }
  cv::FileStorage fs;
  try {
    fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": not a readable calibration YAML file (" + e.err + ")");
  }
  if (!fs.isOpened()) throw std::runtime_error(path + ": cannot open calibration file");
  Calibration c;
  c.A = ReadNumber(fs, "A", path);
  c.B = ReadNumber(fs, "B", path);
  c.C = ReadNumber(fs, "C", path);
  c.D = ReadNumber(fs, "D", path);
  const std::vector<double> K = ReadMatrix(fs, "K_ir", 3, 3, path);  // row-major
  c.fx = K[0];
  c.fy = K[4];
  c.cx = K[2];
  c.cy = K[5];
  if (!fs["dist_ir"].empty()) {
    const std::vector<double> dist = ReadMatrix(fs, "dist_ir", 1, 5, path);  // or 5x1
    std::copy(dist.begin(), dist.end(), c.dist_ir.begin());
  }
  c.min_depth_m = ReadNumber(fs, "min_depth_m", path);
  c.max_depth_m = ReadNumber(fs, "max_depth_m", path);
  if (!fs["depth_units_per_m"].empty()) {
    c.depth_units_per_m = ReadNumber(fs, "depth_units_per_m", path);
    if (!(c.depth_units_per_m > 0))
      throw std::runtime_error(path + ": field 'depth_units_per_m' must be > 0");
  }
  if (!fs["description"].empty()) c.description = static_cast<std::string>(fs["description"]);
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
