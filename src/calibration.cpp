#include "rgbdvo/calibration.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>

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
}

Calibration LoadCalibration(const std::string& path) {
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": not a readable calibration YAML file (" + e.err + ")");
  }
  if (!fs.isOpened()) throw std::runtime_error(path + ": cannot open calibration file");
  Calibration c;
  c.A = ReadNumber(fs, "A", path);
  c.B = ReadNumber(fs, "B", path);
  c.C = ReadNumber(fs, "C", path);
  c.D = ReadNumber(fs, "D", path);
  cv::Mat K;
  fs["K_ir"] >> K;
  if (K.rows != 3 || K.cols != 3)
    throw std::runtime_error(path + ": field 'K_ir' must be a 3x3 matrix");
  K.convertTo(K, CV_64F);
  c.fx = K.at<double>(0, 0);
  c.fy = K.at<double>(1, 1);
  c.cx = K.at<double>(0, 2);
  c.cy = K.at<double>(1, 2);
  if (!fs["dist_ir"].empty()) {
    cv::Mat dist;
    fs["dist_ir"] >> dist;
    if (dist.total() != 5) throw std::runtime_error(path + ": field 'dist_ir' must have 5 values");
    dist.convertTo(dist, CV_64F);
    for (int i = 0; i < 5; ++i) c.dist_ir[i] = dist.at<double>(i);
  }
  c.min_depth_m = ReadNumber(fs, "min_depth_m", path);
  c.max_depth_m = ReadNumber(fs, "max_depth_m", path);
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
}

}  // namespace rgbdvo
