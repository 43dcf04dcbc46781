#include "rgbdvo/sensor/principal_point_check.hpp"

#include <cmath>
#include <sstream>

namespace rgbdvo {

std::optional<std::string> CheckPrincipalPoint(const Calibration& calib, int width, int height) {
  if (width <= 0 || height <= 0) return std::nullopt;
  const double off_u = std::abs(calib.cx - 0.5 * (width - 1));
  const double off_v = std::abs(calib.cy - 0.5 * (height - 1));
  if (off_u <= 0.25 * width && off_v <= 0.25 * height) return std::nullopt;
  std::ostringstream s;
  s << "the calibration's principal point (" << calib.cx << ", " << calib.cy
    << ") is far from the centre of the " << width << "x" << height
    << " depth image (a camera's lies within a few per cent of it): a calibration made for "
       "another image size? fx, fy, cx and cy scale with the image size";
  return s.str();
}

}  // namespace rgbdvo
