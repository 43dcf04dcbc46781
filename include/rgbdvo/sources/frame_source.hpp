#pragma once
// A sequence of frames: a recorded folder or a live device.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rgbdvo/sources/frame.hpp"

namespace rgbdvo {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame, or nullopt at the end. Throws std::runtime_error naming the file or the
  // cause when a frame exists but cannot be read (corrupt image, wrong size, device lost).
  virtual std::optional<Frame> Next() = 0;
  // One line: what is read and how (for the configuration printed at the start of a run).
  virtual std::string Describe() const = 0;
  // Passes over the next frame; false at the end. Recorded folders skip without reading the
  // images; the default reads the frame and drops it.
  virtual bool Skip() { return Next().has_value(); }
  // Frames in all (read or not), when known in advance (recorded folders); nullopt for a live
  // device.
  virtual std::optional<size_t> Size() const { return std::nullopt; }
  // The image files the frames are read from, when known in advance (recorded folders): no
  // output may overwrite them. Empty for a device or a single file.
  virtual std::vector<std::string> Files() const { return {}; }
};

}  // namespace rgbdvo
