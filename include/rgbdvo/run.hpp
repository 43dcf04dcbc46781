#pragma once
// The body of `rgbdvo run`: a source through the odometry into the writers.

#include <functional>
#include <string>
#include <vector>

#include "rgbdvo/frame_source.hpp"
#include "rgbdvo/odometry.hpp"
#include "rgbdvo/trajectory_writer.hpp"

namespace rgbdvo {

struct RunOptions {
  // 1 = decode, features and odometry in turn on the calling thread. 2 = a two-stage pipeline:
  // a second thread decodes frame k+1 and extracts its features while the calling thread
  // matches, estimates and writes frame k (identical results, same order). 0 = the hardware
  // concurrency capped at 2.
  int threads = 0;
  int queue_frames = 2;  // frames decoded ahead of the odometry at most (bounds memory), >= 1
  void Check() const;
  int EffectiveThreads() const;  // threads, with 0 resolved
};

struct RunSummary {
  int frames = 0;
  int accepted = 0;         // includes the first frame
  int rejected = 0;         // rejected or lost
  double mean_inliers = 0;  // over frames after the first
  double seconds = 0;       // wall time, decoding and writing included
  int threads = 1;          // as run
  // Seconds summed over frames, each measured on the thread doing it (with 2 threads decoding
  // and features overlap the other stages, so the sum can exceed `seconds`).
  StageTimes stage_seconds;
  double decode_seconds = 0, write_seconds = 0;
  std::string Brief() const;   // one line: frames, accepted, rejected, mean inliers, fps
  std::string Timing() const;  // one line: milliseconds per frame for each stage
};

// Runs until the source ends. Each result goes to every writer (flushed) and then to
// `on_frame` (may be empty), in frame order. Exceptions from the source or writers propagate
// (a source error only after every frame before it is written); rows already written stay on
// disk.
RunSummary RunOdometry(FrameSource& source, Odometry& odometry,
                       const std::vector<TrajectoryWriter*>& writers,
                       const std::function<void(const FrameResult&)>& on_frame = {},
                       const RunOptions& options = {});

}  // namespace rgbdvo
