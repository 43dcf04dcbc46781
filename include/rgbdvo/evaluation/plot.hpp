#pragma once
// Trajectory figures: top view and side view of a path, the estimate and the (rigidly aligned)
// ground truth overlaid, drawn by gnuplot (pngcairo terminal) from a generated script.

#include <string>
#include <vector>

#include "rgbdvo/evaluation/evaluation.hpp"
#include "rgbdvo/io/trajectory_io.hpp"

namespace rgbdvo {

struct PlotOptions {
  std::string title;    // figure title; empty = "trajectory"
  int width_px = 1300;  // PNG size, pixels
  int height_px = 720;
  double max_dt_s = 0.02;           // time matching for aligning the ground truth, s
  std::string gnuplot = "gnuplot";  // the gnuplot executable (name on PATH or a path)
  void Check() const;               // throws naming the field
};

struct PlotResult {
  std::string png_path;
  int estimate_poses = 0;     // one per timestamp (the last), as in the file read back
  int groundtruth_poses = 0;  // 0 when no ground truth was given
  bool aligned = false;       // ground truth drawn, aligned to the estimate by the ATE fit
  AteResult ate;              // the fit used for the alignment
  std::string Brief() const;
};

// Writes a PNG with two panels in the estimate's world frame (the first camera: x right, y down,
// z forward): a top view (x against z) and a side view (z against up = -y), equal scale on both
// axes, start and end of the estimate marked, a legend. `groundtruth` may be empty; it is mapped
// into the estimate's frame by the inverse of the ATE alignment (ComputeAte) and left out, with
// the reason in the result, when fewer than 3 poses match in time. Throws when gnuplot is
// missing or fails, naming the command and its message.
PlotResult PlotTrajectory(const std::vector<StampedPose>& estimate,
                          const std::vector<StampedPose>& groundtruth, const std::string& png_path,
                          const PlotOptions& options);

}  // namespace rgbdvo
