#pragma once
// The body of `rgbdvo run`: a source through the odometry into the writers.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/pipeline/trajectory_writer.hpp"
#include "rgbdvo/sources/frame_source.hpp"

namespace rgbdvo {

struct RunOptions {
  // 1 = decode, features and odometry in turn on the calling thread. N >= 2 = N feature
  // workers: each takes the next frame from the source (one at a time, so frames keep their
  // order), decodes it and extracts its features; the calling thread takes the frames strictly
  // in order, matches, estimates and writes. Results are identical for every value. 0 =
  // automatic: the hardware concurrency, at least 1 and at most kMaxAutoThreads.
  int threads = 0;
  // Frames read from the source ahead of the odometry at most (decoding, extracting or waiting
  // their turn), raised to the number of workers when smaller; bounds memory. With a live
  // source keep it small: a backlog should wait in the source's queue, where the newest frame
  // wins (rgbdvo capture uses the number of workers). 2: decoding alone (SIFT runs where the
  // odometry needs it) keeps well ahead of the odometry; each frame more in flight is 2.7 MB
  // whose pages are faulted in once more (docs/decisions/0045-page-faults-and-huge-pages.md).
  int queue_frames = 2;
  // With 2 or more threads and tracking between keyframes: a new keyframe's SIFT and the frame
  // before's (for the keyframe fusion) run side by side on two threads (Odometry::SetThreads).
  // Off by default: it shortens those frames, but where the two processors share their memory
  // or other work runs, the two runs slow each other and cost CPU
  // (docs/decisions/0046-keyframe-sift-one-after-the-other.md).
  bool parallel_keyframe_sift = false;
  static constexpr int kMaxAutoThreads = 4;  // more workers gain nothing: decoding is serial
  void Check() const;
  int EffectiveThreads() const;  // threads, with 0 resolved
  // Frames read ahead at most with `EffectiveThreads()` (0 with one thread).
  int EffectiveQueueFrames() const;
  // One line, as resolved: "1 thread" or "2 feature workers + the main thread, at most 4
  // frames read ahead".
  std::string Describe() const;
};

// Distribution of non-negative values (pixel errors) in fixed bins, bounded memory however long
// the run: 0.1 px bins up to 100 px, the last bin holding everything beyond.
struct ErrorHistogram {
  static constexpr double kBin = 0.1;
  static constexpr int kBins = 1001;
  std::vector<int64_t> counts = std::vector<int64_t>(kBins, 0);
  int64_t n = 0;
  double max = 0;
  void Add(double value);
  // The upper edge of the bin holding the q-quantile (q in [0, 1]), so at most kBin above the
  // exact value (or `max` for the last bin); 0 when empty.
  double Quantile(double q) const;
};

struct RunSummary {
  int frames = 0;
  int accepted = 0;   // includes the first frame
  int recovered = 0;  // estimated against the last accepted frame (FrameStatus)
  int depth = 0;      // features failed, depth images aligned by ICP
  int predicted = 0;  // no estimate: at the constant-velocity prediction
  int rejected = 0;   // no estimate: held at the last pose (--preset paper)
  int lost = 0;       // references given up
  int longest_gap_frames = 0;
  double longest_gap_seconds = 0;
  // With the planar motion model: frames where the 6-DOF estimates left the plane beyond
  // PlanarityCheck's bounds, and how many times that began.
  int non_planar_frames = 0, non_planar_episodes = 0;
  double mean_inliers = 0;  // over frames after the first
  double seconds = 0;       // wall time, decoding and writing included
  int threads = 1;          // as run
  // Seconds summed over frames, each measured on the thread doing it (with workers, decoding
  // and features overlap the other stages, so the sum can exceed `seconds`).
  StageTimes stage_seconds;
  double decode_seconds = 0, write_seconds = 0;
  // Time the calling thread waited for the next frame's features (0 with one thread): near
  // `seconds` when the workers are the bottleneck, near 0 when the odometry is.
  double wait_seconds = 0;
  // Frames the trajectory files left out (most of any writer: TrajectoryWriter::rows_left_out),
  // with --stamp depth those sharing a depth image with the frame before.
  int rows_left_out = 0;
  int fallbacks = 0;  // estimates redone with brute-force matching (FrameResult::fallbacks)
  int frames_with_fallback = 0;
  int rematches = 0;  // estimates redone around the first estimate (FrameResult::rematches)
  // With tracking between keyframes (FrameResult::from_tracks, sift_runs): frames whose pose
  // came from tracks, and SIFT extractions the odometry ran.
  int frames_from_tracks = 0;
  int sift_runs = 0;
  // Prediction error of the final inliers of accepted frames (FrameResult::prediction_error_px).
  ErrorHistogram prediction_error_px;
  // One line: frames, each status, the longest gap, mean inliers, fps (and the rows left out of
  // the trajectory files, if any).
  std::string Brief() const;
  std::string Timing() const;  // one line: milliseconds per frame for each stage
  // One line: brute-force fallbacks, estimates matched again and percentiles of the prediction
  // error (and with tracking: frames from tracks, SIFT extractions).
  std::string Matching() const;
};

// Runs until the source ends. Each result goes to every writer (flushed) and then to
// `on_frame` (may be empty), in frame order. Exceptions from the source or writers propagate
// (a source error only after every frame before it is written); rows already written stay on
// disk. The odometry may use as many threads as the run (Odometry::SetThreads).
RunSummary RunOdometry(FrameSource& source, Odometry& odometry,
                       const std::vector<TrajectoryWriter*>& writers,
                       const std::function<void(const FrameResult&)>& on_frame = {},
                       const RunOptions& options = {},
                       const std::function<void(const std::string&)>& on_warning = {});

}  // namespace rgbdvo
