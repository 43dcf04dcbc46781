#pragma once
// Random access over a forward-only FrameSource: frames are read on demand and kept, so a viewer
// can step back and forth (about 2 MB per 640x480 frame).

#include <vector>

#include "rgbdvo/sources/frame_source.hpp"

namespace rgbdvo {

class FrameCache {
 public:
  explicit FrameCache(FrameSource& source) : source_(source) {}
  // Frame i (0-based), reading the source up to it; nullptr when the source ends before i.
  // Exceptions from the source propagate.
  const Frame* At(int i);
  // Frames read so far; the source's length once At() has returned nullptr.
  int size() const { return static_cast<int>(frames_.size()); }
  bool ended() const { return ended_; }

 private:
  FrameSource& source_;
  std::vector<Frame> frames_;
  bool ended_ = false;
};

}  // namespace rgbdvo
