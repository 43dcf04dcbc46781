#pragma once
// Keypoints followed from one image into another by pyramidal Lucas-Kanade (OpenCV's): between
// keyframes the keyframe's keypoints are tracked into each frame instead of SIFT being run and
// matched there (OdometryOptions::track_between_keyframes;
// docs/decisions/0038-tracking-by-default.md).

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "rgbdvo/features/lucas_kanade.hpp"

namespace rgbdvo {

struct TrackOptions {
  // The Lucas-Kanade window's side, pixels. A SIFT keypoint is the centre of a blob of about
  // its scale (2-3 px at the finest); 9, 11 and 13 px track about equally well
  // (docs/decisions/0032-track-option.md), the cost grows with the area.
  int window_px = 9;
  // Pyramid levels above the image: each halves the motion the window has to catch (3: a
  // prediction off by up to about 8 window sides is still caught).
  int levels = 3;
  // > 0: a track is kept only when tracking it back from where it landed returns within this
  // distance of where it started, pixels (twice the work). 0: not checked; RANSAC and the
  // refinement's inlier selection sort the tracks, and measured that is better: the check
  // drops right tracks in motion blur (docs/decisions/0032-track-option.md).
  double max_back_error_px = 0;
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

// A CV_8UC1 copy of a BGR (as SIFT converts it) or grey image; throws std::invalid_argument on
// an empty one.
cv::Mat GreyImage(const cv::Mat& image);

// The grey image's pyramid (cv::buildOpticalFlowPyramid), made once per frame. Lucas-Kanade
// needs the derivatives of the image it tracks from, not of the one it tracks into: most
// frames are only tracked into, so the derivatives are made where a frame is tracked from
// (with_derivatives; without them TrackPoints would compute them again at every call).
TrackingPyramid MakeTrackingPyramid(const TrackOptions& options, const cv::Mat& grey,
                                    bool with_derivatives);
// HasDerivatives (features/lucas_kanade.hpp) tells a pyramid made with_derivatives.

// Up to max_points indices of the keypoints with usable[i], spread over the image (size):
// the image split into an 8 x 8 grid, the strongest remaining keypoint of each cell taken in
// turn (by response, ties by index), cell by cell, until max_points or none are left.
std::vector<int> SelectSpread(const std::vector<cv::KeyPoint>& keypoints,
                              const std::vector<bool>& usable, cv::Size size, int max_points);

// Each of `points` (pixels of `from`) tracked into `to`, starting from guess[i]: where it lies
// in `to`, or nullopt when Lucas-Kanade lost it, it left the image, or (with
// max_back_error_px) tracking it back from there lands farther than that from where it started.
// Lucas-Kanade is OpenCV's (features/lucas_kanade.hpp: with the derivatives in `from`, the same
// tracks from windows made here).
std::vector<std::optional<cv::Point2f>> TrackPoints(const TrackOptions& options,
                                                    const TrackingPyramid& from,
                                                    const TrackingPyramid& to,
                                                    const std::vector<cv::Point2f>& points,
                                                    const std::vector<cv::Point2f>& guess);
// The Lucas-Kanade windows of `points` in `from` (a pyramid with derivatives), to track them
// into many images: made once per keyframe, they save a quarter of Lucas-Kanade's work a frame.
LkWindows MakeTrackingWindows(const TrackOptions& options, const TrackingPyramid& from,
                              const std::vector<cv::Point2f>& points);
// As TrackPoints above, from windows made by MakeTrackingWindows (one guess per point): the same
// tracks.
std::vector<std::optional<cv::Point2f>> TrackPoints(const TrackOptions& options,
                                                    const LkWindows& from,
                                                    const TrackingPyramid& to,
                                                    const std::vector<cv::Point2f>& guess);

// Each landed point refined in `to` (CV_8UC1, the finest level) with the window of `from` seen
// as `to` sees it: the window's offset w around the landing shows what offset warp[i]^-1 w
// around points[i] shows in `from` (warp[i]: the local affine map of `from`'s pixels onto
// `to`'s, from the predicted motion; odometry/point_pairs.hpp PredictWarps). Translational
// Lucas-Kanade on that warped template, warp_window_px wide. A point whose window leaves either
// image, whose template has no texture, or whose refinement does not settle within warp_iterations
// and warp_max_shift_px of where it landed keeps its landing.
void RefineWarped(const TrackOptions& options, const cv::Mat& from, const cv::Mat& to,
                  const std::vector<cv::Point2f>& points, const std::vector<cv::Matx22f>& warp,
                  std::vector<std::optional<cv::Point2f>>* landed);

}  // namespace rgbdvo
