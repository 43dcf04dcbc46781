#pragma once
// A plausibility check of the calibration against the images: K_ir belongs to one image size.
// Read with images of another size (a calibration made at 640x480 for a recording at 320x240,
// or the other way round) the focal lengths and principal point are off by that factor and the
// trajectory is wrong, silently. A real camera's principal point lies within a few per cent of
// the image centre; at half or twice the calibration's size it lies a quarter of the image or
// more away from it.

#include <optional>
#include <string>

#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

// A message when the calibration's principal point (cx, cy) is more than a quarter of the depth
// image's width or height away from its centre, nullopt otherwise (also for an empty size).
std::optional<std::string> CheckPrincipalPoint(const Calibration& calib, int width, int height);

}  // namespace rgbdvo
