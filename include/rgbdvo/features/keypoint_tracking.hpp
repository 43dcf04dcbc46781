#pragma once
// Keypoints followed from one image into another by pyramidal Lucas-Kanade (OpenCV's): between
// keyframes the keyframe's keypoints are tracked into each frame instead of SIFT being run and
// matched there (OdometryOptions::track_between_keyframes;
// docs/decisions/0038-tracking-by-default.md).

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "rgbdvo/features/lucas_kanade.hpp"
#include "rgbdvo/features/track_options.hpp"

namespace rgbdvo {

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
// in `to`, or nullopt when Lucas-Kanade lost it or it left the image. No forward-backward check:
// RANSAC and the refinement's inlier selection sort the tracks, and the check drops right tracks
// in motion blur (docs/decisions/0032-track-option.md).
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
