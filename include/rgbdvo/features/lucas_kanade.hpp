#pragma once
// Pyramidal Lucas-Kanade as OpenCV's cv::calcOpticalFlowPyrLK computes it, bit for bit, in two
// steps: the windows of the points in the image tracked from (at every pyramid level their
// values, derivatives and 2 x 2 normal matrix), made once, then the tracking of those windows
// into any number of images. Between keyframes every frame tracks the same keyframe points, and
// OpenCV made their windows again for each frame (a quarter of its work).

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace rgbdvo {

// The grey image's pyramid, as cv::buildOpticalFlowPyramid makes it (with or without the
// derivatives after each level).
using TrackingPyramid = std::vector<cv::Mat>;
// True when every level is followed by its 2-channel 16-bit Scharr derivatives (OpenCV's test).
bool HasDerivatives(const TrackingPyramid& pyramid);

struct LkWindows {
  cv::Size window;
  int levels = -1;                  // the coarsest level made (0 = the image itself)
  TrackingPyramid from;             // made with derivatives (shares the images)
  std::vector<cv::Point2f> points;  // where the windows are centred, finest level's pixels
  // Per level and point ([level * points.size() + i]): whether the window is inside the image
  // and textured (OpenCV's smallest-eigenvalue test), the normal matrix, its inverse determinant.
  std::vector<uint8_t> usable;
  std::vector<float> a11, a12, a22, inv_det;
  // The windows' values (x 32) and derivatives (x, y pairs), window.area() and 2 x area a point
  // and level, in the same order.
  std::vector<int16_t> values, derivs;
};

// The windows of `points` at levels 0 .. levels of `from` (a pyramid with derivatives, built with
// window; fewer levels where the pyramid has fewer). Throws std::invalid_argument without
// derivatives.
LkWindows MakeLkWindows(const TrackingPyramid& from, cv::Size window, int levels,
                        const std::vector<cv::Point2f>& points);

// The windows tracked into `to` (a pyramid of the same image size, with or without derivatives):
// next[i] holds where to start (finest level's pixels) and receives where the point landed;
// found[i] = 0 where OpenCV's status is 0. Equal bit for bit to cv::calcOpticalFlowPyrLK(from,
// to, points, next, found, cv::noArray(), window, levels, {COUNT + EPS, max_iterations,
// epsilon}, OPTFLOW_USE_INITIAL_FLOW) on x86-64; elsewhere that call itself.
void TrackLkWindows(const LkWindows& windows, const TrackingPyramid& to, int max_iterations,
                    double epsilon, std::vector<cv::Point2f>* next, std::vector<uchar>* found);

}  // namespace rgbdvo
