#pragma once
// Runs of frames without a feature estimate (icp, predicted, rejected, lost): when they start
// and end, and the longest, so that no failure goes unreported.

#include <optional>
#include <string>

#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo {

class TrackingGaps {
 public:
  // Feeds the next frame's result (in frame order). Returns a one-line warning when a gap starts
  // ("tracking failed at t=... (frame N): reason; reporting predicted poses", or what else
  // carries the pose) or ends ("tracking resumed at t=... (frame N) after K frames without a
  // feature estimate (S s between feature estimates)", or "since the first frame" for a gap
  // the sequence begins with).
  std::optional<std::string> Add(const FrameResult& result);
  // A warning for a gap still open at the end of the sequence, if any.
  std::optional<std::string> Finish() const;

  int longest_frames() const { return longest_frames_; }
  // The longest time between the feature estimates either side of a gap (for a gap at the end,
  // from the last feature estimate to the last frame; for a gap at the start, from the first
  // frame): what the fallbacks had to bridge. A frame's timestamp is its colour image's.
  double longest_seconds() const { return longest_seconds_; }
  int gaps() const { return gaps_; }

 private:
  bool open_ = false;
  int run_frames_ = 0;
  std::optional<double> estimate_time_;  // the last frame with a feature estimate
  bool gap_at_start_ = false;            // the open gap began with the first frame
  double last_time_ = 0;                 // the last frame of the open gap
  int longest_frames_ = 0;
  double longest_seconds_ = 0;
  int gaps_ = 0;
};

}  // namespace rgbdvo
