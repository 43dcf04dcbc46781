#pragma once
// Opens a recorded folder, detecting its layout.

#include <memory>
#include <string>

#include "rgbdvo/sources/fakenect_source.hpp"
#include "rgbdvo/sources/frame_source.hpp"
#include "rgbdvo/sources/tum_source.hpp"

namespace rgbdvo {

struct SourceOptions {
  TumSourceOptions tum;
  FakenectSourceOptions fakenect;
};

// TUM RGB-D layout (rgb.txt + depth.txt) or libfreenect fakenect layout (INDEX.txt). Throws
// std::runtime_error naming the folder when it is missing or of no known layout.
std::unique_ptr<FrameSource> OpenRecording(const std::string& folder, const SourceOptions& options);

}  // namespace rgbdvo
