// Writes a TUM RGB-D folder as a ROS 2 bag (sources/tum_to_ros2.hpp): an MCAP file (chunks
// zstd, lz4 or none) or an sqlite3 .db3 file, depth 32FC1 metres or 16UC1 millimetres, with
// camera_info, for running `rgbdvo run` on ROS 2 bags.
//   rgbdvo_tum_to_ros2 FOLDER OUT.mcap|OUT.db3 [--compression zstd|lz4|none]
//                      [--depth 32FC1|16UC1] [--no-camera-info] [--fx F --fy F --cx C --cy C]
#include "rgbdvo/sources/tum_to_ros2.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

namespace {

int Run(int argc, char** argv) {
  CLI::App app("TUM RGB-D folder -> ROS 2 bag (MCAP or sqlite3 .db3, by OUT's extension)");
  std::string folder, out, compression = "zstd";
  bool no_camera_info = false;
  rgbdvo::TumToRos2Options options;
  app.add_option("folder", folder, "TUM RGB-D folder (rgb.txt, depth.txt)")->required();
  app.add_option("out", out, "the bag: .mcap or .db3")->required();
  app.add_option("--compression", compression, "MCAP chunks: zstd, lz4 or none")
      ->check(CLI::IsMember({"zstd", "lz4", "none"}))
      ->capture_default_str();
  app.add_option("--depth", options.depth_encoding, "depth encoding: 32FC1 (m) or 16UC1 (mm)")
      ->check(CLI::IsMember({"32FC1", "16UC1"}))
      ->capture_default_str();
  app.add_flag("--no-camera-info", no_camera_info, "write no camera_info topics");
  app.add_option("--fx", options.fx)->capture_default_str();
  app.add_option("--fy", options.fy)->capture_default_str();
  app.add_option("--cx", options.cx)->capture_default_str();
  app.add_option("--cy", options.cy)->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  options.compression = compression == "none" ? "" : compression;
  options.camera_info = !no_camera_info;
  options.storage = std::filesystem::path(out).extension() == ".db3" ? "sqlite3" : "mcap";
  try {
    const size_t frames = rgbdvo::WriteTumAsRos2Bag(folder, out, options);
    std::cout << out << ": " << frames << " frames" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "rgbdvo_tum_to_ros2: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {  // the command line's own set-up failing
    std::cerr << "rgbdvo_tum_to_ros2: " << e.what() << std::endl;
    return 1;
  }
}
