#include "rgbdvo/sources/frame_cache.hpp"

namespace rgbdvo {

const Frame* FrameCache::At(int i) {
  if (i < 0) return nullptr;
  while (!ended_ && static_cast<int>(frames_.size()) <= i) {
    std::optional<Frame> f = source_.Next();
    if (f)
      frames_.push_back(std::move(*f));
    else
      ended_ = true;
  }
  return i < size() ? &frames_[i] : nullptr;
}

}  // namespace rgbdvo
