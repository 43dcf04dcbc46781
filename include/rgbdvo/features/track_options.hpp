#pragma once
// How the keyframe's keypoints are tracked between keyframes (keypoint_tracking.hpp).

namespace rgbdvo {

struct TrackOptions {
  // The Lucas-Kanade window's side, pixels. A SIFT keypoint is the centre of a blob of about
  // its scale (2-3 px at the finest); 9, 11 and 13 px track about equally well
  // (docs/decisions/0032-track-option.md), the cost grows with the area.
  int window_px = 9;
  // Pyramid levels above the image: each halves the motion the window has to catch (3: a
  // prediction off by up to about 8 window sides is still caught).
  int levels = 3;
  // At most this many of the keyframe's keypoints (with a 3D point) are tracked: the strongest of
  // each cell of an 8 x 8 grid in turn, so that they cover the image as the matches do.
  int max_points = 400;
  // true: after the pyramid, each track is refined at the finest level with the keyframe's
  // window warped as the predicted motion shows it (RefineWarped). OpenCV's window only shifts:
  // as the view moves on from the keyframe, its content grows, shrinks and shears, and the track
  // slides away from its keyframe as the keyframe ages (docs/decisions/0036-warped-window.md).
  // false = OpenCV's shifted window alone.
  bool warp = true;
  // The refinement's iterations at most, and how far it may move a track, pixels: farther, it
  // has left the place the pyramid found, and the pyramid's landing stands.
  int warp_window_px = 9;
  // Refined only where the warp moves a corner of the window at least this far from where a
  // shift puts it, pixels (elsewhere the shifted window fits as well).
  double warp_min_px = 0.1;
  // Settled when a step moves the track less than warp_settled_px, within warp_iterations.
  double warp_settled_px = 0.01;
  int warp_iterations = 10;
  double warp_max_shift_px = 2.0;
  void Check() const;
};

}  // namespace rgbdvo
