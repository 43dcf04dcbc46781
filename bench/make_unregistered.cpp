// Writes a TUM RGB-D folder with registered depth as a Kinect v1 without registration would
// record it, for measuring `rgbdvo run` on unregistered depth: each depth image is rendered
// again in a virtual IR camera (its own focal length and principal point, no lens distortion)
// beside the colour camera with parallel axes, and two calibrations of that camera are written
// next to it: calib_disparity.yaml (eq. 1 with the disparity term s_u, exact for undistorted
// colour pixels) and calib_eq1.yaml (eq. 1 alone, B fitted at 1.5 m, as the paper's). The colour
// images (linked, not copied), the lists and the ground truth are the folder's. The colour
// camera's lens distortion (dist_ir of the registered calibration) is undone when the depth is
// lifted, but eq. 1 maps the colour image's pixels as they are, as on a real Kinect;
// --undistort-colour writes undistorted colour images instead, which eq. 1 maps exactly.
//   rgbdvo_make_unregistered FOLDER CALIB.yaml OUT [--fx 580 --fy FX --cx 320 --cy 240]
//                            [--baseline 0.025] [--undistort-colour]
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sensor/camera.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  try {
    CLI::App app("TUM folder with registered depth -> the same recording with unregistered depth");
    std::string folder, calib_path, out;
    double f_ir = 580, fy_ir = 0, cx_ir = 320, cy_ir = 240, baseline = 0.025, depth_scale = 5000;
    app.add_option("folder", folder)->required();
    app.add_option("calib", calib_path, "the folder's (registered) calibration")->required();
    app.add_option("out", out)->required();
    app.add_option("--fx", f_ir, "virtual IR camera's focal length, px");
    app.add_option("--fy", fy_ir, "its vertical focal length, px (default: --fx)");
    app.add_option("--cx", cx_ir);
    app.add_option("--cy", cy_ir);
    app.add_option("--baseline", baseline, "IR camera's offset along the colour camera's x, m");
    bool undistort_colour = false;
    app.add_flag("--undistort-colour", undistort_colour,
                 "write the colour images with their lens distortion removed (same K), so that "
                 "eq. 1 maps them exactly, instead of linking the folder's");
    CLI11_PARSE(app, argc, argv);
    const rgbdvo::Calibration colour = rgbdvo::LoadCalibration(calib_path);
    if (fy_ir <= 0) fy_ir = f_ir;
    for (const char* dir : {"rgb", "depth"})
      if (!fs::is_directory(fs::path(folder) / dir))
        throw std::runtime_error(folder + ": no " + dir +
                                 "/ folder (a TUM RGB-D folder is needed)");
    fs::create_directories(fs::path(out) / "depth");
    for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt"})
      if (fs::exists(fs::path(folder) / name))
        fs::copy_file(fs::path(folder) / name, fs::path(out) / name,
                      fs::copy_options::overwrite_existing);
    if (undistort_colour) {
      fs::create_directories(fs::path(out) / "rgb");
      const cv::Matx33d K(colour.fx, 0, colour.cx, 0, colour.fy, colour.cy, 0, 0, 1);
      for (const fs::directory_entry& e : fs::directory_iterator(fs::path(folder) / "rgb")) {
        cv::Mat undistorted;
        cv::undistort(cv::imread(e.path().string()), undistorted, K, colour.dist_ir);
        cv::imwrite((fs::path(out) / "rgb" / e.path().filename()).string(), undistorted);
      }
    } else if (!fs::exists(fs::path(out) / "rgb")) {
      fs::create_directory_symlink(fs::absolute(fs::path(folder) / "rgb"), fs::path(out) / "rgb");
    }
    cv::Mat rays;  // the undistorted normalised ray of every colour pixel
    int frames = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::path(folder) / "depth")) {
      const cv::Mat raw = cv::imread(e.path().string(), cv::IMREAD_UNCHANGED);
      if (raw.type() != CV_16UC1) throw std::runtime_error(e.path().string() + ": not 16-bit");
      if (rays.empty()) {
        rays.create(raw.size(), CV_64FC2);
        for (int v = 0; v < raw.rows; ++v)
          for (int u = 0; u < raw.cols; ++u) {
            const Eigen::Vector2d x = rgbdvo::NormalizeIr(colour, {u, v});
            rays.at<cv::Vec2d>(v, u) = {x.x(), x.y()};
          }
      }
      // Each colour pixel covers a square of the IR image (its side: the focal lengths' ratio,
      // a tenth more so that lens distortion leaves no cracks); the IR pixels whose centres it
      // covers take its depth, the nearest where several do.
      const double half_u = 0.55 * f_ir / colour.fx, half_v = 0.55 * fy_ir / colour.fy;
      cv::Mat z_ir(raw.size(), CV_64FC1, cv::Scalar(std::numeric_limits<double>::infinity()));
      for (int v = 0; v < raw.rows; ++v)
        for (int u = 0; u < raw.cols; ++u) {
          const double z = raw.at<uint16_t>(v, u) / depth_scale;
          if (z <= 0) continue;
          const cv::Vec2d x = rays.at<cv::Vec2d>(v, u);
          const double u_ir = f_ir * (x[0] * z - baseline) / z + cx_ir;
          const double v_ir = fy_ir * x[1] + cy_ir;
          const int u0 = std::max(0, static_cast<int>(std::ceil(u_ir - half_u)));
          const int u1 = std::min(raw.cols, static_cast<int>(std::ceil(u_ir + half_u)));
          const int v0 = std::max(0, static_cast<int>(std::ceil(v_ir - half_v)));
          const int v1 = std::min(raw.rows, static_cast<int>(std::ceil(v_ir + half_v)));
          for (int vv = v0; vv < v1; ++vv)
            for (int uu = u0; uu < u1; ++uu) {
              double& d = z_ir.at<double>(vv, uu);
              d = std::min(d, z);
            }
        }
      cv::Mat depth(raw.size(), CV_16UC1);
      for (int v = 0; v < raw.rows; ++v)
        for (int u = 0; u < raw.cols; ++u) {
          const double z = z_ir.at<double>(v, u);
          depth.at<uint16_t>(v, u) =
              std::isfinite(z) ? static_cast<uint16_t>(std::lround(z * depth_scale)) : 0;
        }
      const fs::path target = fs::path(out) / "depth" / e.path().filename();
      if (!cv::imwrite(target.string(), depth))
        throw std::runtime_error("cannot write " + target.string());
      ++frames;
    }
    // u_ir = (f_ir / f) (u - cx) + cx_ir + s_u / z with s_u = -f_ir * baseline (undistorted u).
    rgbdvo::Calibration ir;
    ir.A = f_ir / colour.fx;
    ir.C = fy_ir / colour.fy;
    ir.B = cx_ir - ir.A * colour.cx;
    ir.D = cy_ir - ir.C * colour.cy;
    ir.s_u = -f_ir * baseline;
    ir.fx = f_ir;
    ir.fy = fy_ir;
    ir.cx = cx_ir;
    ir.cy = cy_ir;
    ir.min_depth_m = colour.min_depth_m;
    ir.max_depth_m = colour.max_depth_m;
    ir.depth_units_per_m = depth_scale;
    ir.description =
        "virtual IR camera of rgbdvo_make_unregistered: exact eq. 1 with the disparity term";
    rgbdvo::SaveCalibration(ir, (fs::path(out) / "calib_disparity.yaml").string());
    ir.B += ir.s_u / 1.5;
    ir.s_u = 0;
    ir.description = "virtual IR camera of rgbdvo_make_unregistered: eq. 1, exact at 1.5 m";
    rgbdvo::SaveCalibration(ir, (fs::path(out) / "calib_eq1.yaml").string());
    std::cout << frames << " depth images -> " << out << "\n";
  } catch (const std::exception& e) {
    std::cerr << "rgbdvo_make_unregistered: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "rgbdvo_make_unregistered: unknown error\n";
    return 1;
  }
  return 0;
}
