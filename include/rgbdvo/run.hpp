#pragma once
// The body of `rgbdvo run`: a source through the odometry into the writers.

#include <functional>
#include <string>
#include <vector>

#include "rgbdvo/frame_source.hpp"
#include "rgbdvo/odometry.hpp"
#include "rgbdvo/trajectory_writer.hpp"

namespace rgbdvo {

struct RunSummary {
  int frames = 0;
  int accepted = 0;  // includes the first frame
  int rejected = 0;  // rejected or lost
  double mean_inliers = 0;  // over frames after the first
  double seconds = 0;       // wall time, decoding and writing included
  StageTimes stage_seconds; // summed over frames
  double decode_seconds = 0, write_seconds = 0;
  std::string Brief() const;  // one line: frames, accepted, rejected, mean inliers, fps
};

// Runs until the source ends. Each result goes to every writer (flushed) and then to
// `on_frame` (may be empty). Exceptions from the source or writers propagate; rows already
// written stay on disk.
RunSummary RunOdometry(FrameSource& source, Odometry& odometry,
                       const std::vector<TrajectoryWriter*>& writers,
                       const std::function<void(const FrameResult&)>& on_frame = {});

}  // namespace rgbdvo
