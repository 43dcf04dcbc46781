#include "rgbdvo/sources/frame_range.hpp"

#include <algorithm>
#include <stdexcept>

namespace rgbdvo {

void FrameRange::Check() const {
  if (start < 0) throw std::invalid_argument("FrameRange.start must be >= 0");
  if (max_frames < 0)
    throw std::invalid_argument("FrameRange.max_frames must be >= 0 (0 = to the end)");
}

FrameRangeSource::FrameRangeSource(std::unique_ptr<FrameSource> inner, const FrameRange& range)
    : inner_(std::move(inner)), range_(range) {
  range_.Check();
}

std::optional<Frame> FrameRangeSource::Next() {
  if (!started_) {
    started_ = true;
    for (int k = 0; k < range_.start; ++k)
      if (!inner_->Skip())
        throw std::runtime_error("start frame " + std::to_string(range_.start) +
                                 " is beyond the recording's end (it has " + std::to_string(k) +
                                 " frames)");
  }
  if (range_.max_frames > 0 && returned_ >= range_.max_frames) return std::nullopt;
  std::optional<Frame> frame = inner_->Next();
  if (!frame && returned_ == 0 && range_.start > 0)  // the recording ended exactly at `start`
    throw std::runtime_error("start frame " + std::to_string(range_.start) +
                             " is beyond the recording's end (it has " +
                             std::to_string(range_.start) + " frames)");
  if (frame) ++returned_;
  return frame;
}

std::optional<size_t> FrameRangeSource::Size() const {
  const std::optional<size_t> all = inner_->Size();
  if (!all) return std::nullopt;
  const size_t start = static_cast<size_t>(range_.start);
  size_t n = *all > start ? *all - start : 0;
  if (range_.max_frames > 0) n = std::min(n, static_cast<size_t>(range_.max_frames));
  return n;
}

std::string FrameRangeSource::Describe() const {
  std::string s = inner_->Describe();
  if (range_.All()) return s;
  s += "; from frame " + std::to_string(range_.start);
  if (range_.max_frames > 0) s += ", at most " + std::to_string(range_.max_frames) + " frames";
  return s;
}

}  // namespace rgbdvo
