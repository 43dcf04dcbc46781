#pragma once
// A part of a recording: from frame `start` (counted from 0), at most `max_frames` frames.

#include <memory>
#include <optional>
#include <string>

#include "rgbdvo/sources/frame_source.hpp"

namespace rgbdvo {

struct FrameRange {
  int start = 0;       // frames passed over first (not read, where the source allows)
  int max_frames = 0;  // 0 = to the end
  bool All() const { return start == 0 && max_frames == 0; }
  void Check() const;  // throws std::invalid_argument naming the field
};

// `inner` within `range`. Frames keep the recording's indices (Frame::index), so a row of a
// partial run names the same frame as in a whole run. The first Next() throws
// std::runtime_error when the recording ends before `start`.
class FrameRangeSource : public FrameSource {
 public:
  FrameRangeSource(std::unique_ptr<FrameSource> inner, const FrameRange& range);
  std::optional<Frame> Next() override;
  std::string Describe() const override;
  std::optional<size_t> Size() const override;  // the frames within the range
  std::vector<std::string> Files() const override { return inner_->Files(); }

 private:
  std::unique_ptr<FrameSource> inner_;
  FrameRange range_;
  bool started_ = false;
  int returned_ = 0;
};

}  // namespace rgbdvo
