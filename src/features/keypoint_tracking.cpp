#include "rgbdvo/features/keypoint_tracking.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

namespace rgbdvo {

void TrackOptions::Check() const {
  if (window_px < 3) throw std::invalid_argument("TrackOptions.window_px must be >= 3");
  if (levels < 0) throw std::invalid_argument("TrackOptions.levels must be >= 0");
  if (!(max_back_error_px >= 0))
    throw std::invalid_argument("TrackOptions.max_back_error_px must be >= 0 (0 = not checked)");
  if (max_points < 1) throw std::invalid_argument("TrackOptions.max_points must be >= 1");
}

cv::Mat GreyImage(const cv::Mat& image) {
  if (image.empty()) throw std::invalid_argument("tracking: empty image");
  cv::Mat grey;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    grey = image.clone();
  return grey;
}

TrackingPyramid MakeTrackingPyramid(const TrackOptions& options, const cv::Mat& grey,
                                    bool with_derivatives) {
  if (grey.type() != CV_8UC1)
    throw std::invalid_argument("tracking: the pyramid is made of a CV_8UC1 image");
  TrackingPyramid pyramid;
  cv::buildOpticalFlowPyramid(grey, pyramid, cv::Size(options.window_px, options.window_px),
                              options.levels, with_derivatives);
  return pyramid;
}

bool HasDerivatives(const TrackingPyramid& pyramid) {
  // With derivatives every level is followed by its 2-channel 16-bit Scharr gradients.
  return pyramid.size() > 1 && pyramid[1].type() == CV_16SC2;
}

std::vector<int> SelectSpread(const std::vector<cv::KeyPoint>& keypoints,
                              const std::vector<bool>& usable, cv::Size size, int max_points) {
  constexpr int kCells = 8;
  std::vector<std::vector<int>> cells(kCells * kCells);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    if (!usable[i]) continue;
    const cv::Point2f& p = keypoints[i].pt;
    const int cx =
        std::clamp(static_cast<int>(p.x * kCells / std::max(size.width, 1)), 0, kCells - 1);
    const int cy =
        std::clamp(static_cast<int>(p.y * kCells / std::max(size.height, 1)), 0, kCells - 1);
    cells[cy * kCells + cx].push_back(static_cast<int>(i));
  }
  size_t deepest = 0;
  for (std::vector<int>& cell : cells) {
    std::stable_sort(cell.begin(), cell.end(),
                     [&](int a, int b) { return keypoints[a].response > keypoints[b].response; });
    deepest = std::max(deepest, cell.size());
  }
  std::vector<int> chosen;
  for (size_t rank = 0; rank < deepest; ++rank)
    for (const std::vector<int>& cell : cells) {
      if (static_cast<int>(chosen.size()) >= max_points) return chosen;
      if (rank < cell.size()) chosen.push_back(cell[rank]);
    }
  return chosen;
}

std::vector<std::optional<cv::Point2f>> TrackPoints(const TrackOptions& options,
                                                    const TrackingPyramid& from,
                                                    const TrackingPyramid& to,
                                                    const std::vector<cv::Point2f>& points,
                                                    const std::vector<cv::Point2f>& guess) {
  std::vector<std::optional<cv::Point2f>> tracked(points.size());
  if (points.empty() || from.empty() || to.empty()) return tracked;
  const cv::Size window(options.window_px, options.window_px);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
  std::vector<cv::Point2f> forward = guess, back = points;
  std::vector<uchar> found, found_back;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(from, to, points, forward, found, error, window, options.levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  const bool check_back = options.max_back_error_px > 0;
  if (check_back)
    cv::calcOpticalFlowPyrLK(to, from, forward, back, found_back, error, window, options.levels,
                             stop, cv::OPTFLOW_USE_INITIAL_FLOW);
  const cv::Size size = to.front().size();
  const double max_back_sq = options.max_back_error_px * options.max_back_error_px;
  for (size_t i = 0; i < points.size(); ++i) {
    const cv::Point2f& p = forward[i];
    if (!found[i] || (check_back && !found_back[i]) ||
        !(p.x >= 0 && p.y >= 0 && p.x <= size.width - 1 && p.y <= size.height - 1))
      continue;
    const cv::Point2f d = back[i] - points[i];
    if (!check_back || d.x * d.x + d.y * d.y <= max_back_sq) tracked[i] = p;
  }
  return tracked;
}

}  // namespace rgbdvo
