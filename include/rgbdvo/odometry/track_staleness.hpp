#pragma once
// When a keyframe's tracks have gone stale: the pixel noise the refinement measures on each
// tracked frame's pairs (EstimateNoiseScale), against the least measured on the keyframe's
// tracked frames so far.

namespace rgbdvo {

class TrackStaleness {
 public:
  // ratio > 0: a frame whose noise exceeds ratio times the least so far is stale.
  explicit TrackStaleness(double ratio) : ratio_(ratio) {}
  // Feeds the next tracked frame's measured noise (px); true when it is stale. The least, not
  // the first: a blurred first tracked frame would raise the bar for the keyframe's whole life.
  bool Stale(double pixel_noise);

 private:
  double ratio_;
  double least_ = -1;  // none measured yet
};

}  // namespace rgbdvo
