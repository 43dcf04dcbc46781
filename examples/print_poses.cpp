// Prints the camera trajectory of a recording as TUM lines (timestamp tx ty tz qx qy qz qw).
// Usage: print_poses RECORDING CALIBRATION   (a TUM RGB-D or fakenect folder; a calibration
// file or the name of an installed one, e.g. tum_fr1)
#include <iostream>

#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sensor/calibration_catalog.hpp"
#include "rgbdvo/sources/open_source.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: " << argv[0] << " RECORDING CALIBRATION\n";
    return 2;
  }
  try {
    const rgbdvo::Calibration calib = rgbdvo::LoadCalibration(rgbdvo::FindCalibration(argv[2]));
    std::unique_ptr<rgbdvo::FrameSource> source = rgbdvo::OpenRecording(argv[1], {});
    rgbdvo::Odometry odometry(rgbdvo::OdometryOptions{}, calib);
    while (std::optional<rgbdvo::Frame> frame = source->Next()) {
      const rgbdvo::FrameResult result = odometry.Process(*frame);
      rgbdvo::WriteTumLine(std::cout, result.timestamp, result.world_from_cam);
    }
  } catch (const std::exception& e) {
    std::cerr << "print_poses: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
