#include "rgbdvo/features/keypoint_tracking.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

#include "rgbdvo/util/simd.hpp"

namespace rgbdvo {

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

namespace {

const cv::TermCriteria kStop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);

// The forward tracks (found, landed at forward[i]) that landed inside an image of `size`.
std::vector<std::optional<cv::Point2f>> Landings(const cv::Size& size,
                                                 const std::vector<cv::Point2f>& forward,
                                                 const std::vector<uchar>& found) {
  std::vector<std::optional<cv::Point2f>> tracked(forward.size());
  for (size_t i = 0; i < forward.size(); ++i) {
    const cv::Point2f& p = forward[i];
    if (found[i] && p.x >= 0 && p.y >= 0 && p.x <= size.width - 1 && p.y <= size.height - 1)
      tracked[i] = p;
  }
  return tracked;
}

}  // namespace

LkWindows MakeTrackingWindows(const TrackOptions& options, const TrackingPyramid& from,
                              const std::vector<cv::Point2f>& points) {
  return MakeLkWindows(from, cv::Size(options.window_px, options.window_px), options.levels,
                       points);
}

std::vector<std::optional<cv::Point2f>> TrackPoints(const TrackOptions& options,
                                                    const LkWindows& from,
                                                    const TrackingPyramid& to,
                                                    const std::vector<cv::Point2f>& guess) {
  if (from.window != cv::Size(options.window_px, options.window_px) ||
      from.points.size() != guess.size())
    throw std::invalid_argument("tracking: windows of another size, or not one guess per point");
  if (guess.empty() || to.empty()) return std::vector<std::optional<cv::Point2f>>(guess.size());
  std::vector<cv::Point2f> forward = guess;
  std::vector<uchar> found;
  TrackLkWindows(from, to, kStop.maxCount, kStop.epsilon, &forward, &found);
  return Landings(to.front().size(), forward, found);
}

std::vector<std::optional<cv::Point2f>> TrackPoints(const TrackOptions& options,
                                                    const TrackingPyramid& from,
                                                    const TrackingPyramid& to,
                                                    const std::vector<cv::Point2f>& points,
                                                    const std::vector<cv::Point2f>& guess) {
  if (points.empty() || from.empty() || to.empty())
    return std::vector<std::optional<cv::Point2f>>(points.size());
  if (HasDerivatives(from))
    return TrackPoints(options, MakeTrackingWindows(options, from, points), to, guess);
  std::vector<cv::Point2f> forward = guess;
  std::vector<uchar> found;
  cv::calcOpticalFlowPyrLK(from, to, points, forward, found, cv::noArray(),
                           cv::Size(options.window_px, options.window_px), options.levels, kStop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  return Landings(to.front().size(), forward, found);
}

namespace {

// Bilinear sample of a CV_8UC1 image at (x, y); the caller keeps 0 <= x < cols - 1 and
// 0 <= y < rows - 1.
float Bilinear(const cv::Mat& image, float x, float y) {
  const int x0 = static_cast<int>(x);
  const int y0 = static_cast<int>(y);
  const float ax = x - static_cast<float>(x0);
  const float ay = y - static_cast<float>(y0);
  const uchar* r0 = image.ptr<uchar>(y0) + x0;
  const uchar* r1 = r0 + image.step[0];
  const float top = static_cast<float>(r0[0]) + ax * static_cast<float>(r0[1] - r0[0]);
  const float bottom = static_cast<float>(r1[0]) + ax * static_cast<float>(r1[1] - r1[0]);
  return top + ay * (bottom - top);
}

bool Inside(const cv::Mat& image, float x, float y) {
  return x >= 0 && y >= 0 && x < static_cast<float>(image.cols - 1) &&
         y < static_cast<float>(image.rows - 1);
}

}  // namespace

RGBDVO_SIMD_CLONES
void RefineWarped(const TrackOptions& options, const cv::Mat& from, const cv::Mat& to,
                  const std::vector<cv::Point2f>& points, const std::vector<cv::Matx22f>& warp,
                  std::vector<std::optional<cv::Point2f>>* landed) {
  if (from.type() != CV_8UC1 || to.type() != CV_8UC1)
    throw std::invalid_argument("tracking: the warped refinement works on CV_8UC1 images");
  if (warp.size() != points.size() || landed->size() != points.size())
    throw std::invalid_argument("tracking: one warp and one landing per point");
  const int half = options.warp_window_px / 2;
  const int side = 2 * half + 3;  // the window and a ring for the template's derivatives
  std::vector<float> templ(static_cast<size_t>(side * side));
  const int width = 2 * half + 1;
  const int n = width * width;
  // The template's derivatives and values, and the residuals, padded to a multiple of 8 with
  // zeros (the padding adds nothing to the sums).
  const size_t padded = (static_cast<size_t>(n) + 7) / 8 * 8;
  std::vector<float> tx(padded, 0.0f), ty(padded, 0.0f), tv(padded, 0.0f), err(padded, 0.0f);
  const float min_px = static_cast<float>(options.warp_min_px);
  const float settled_sq = static_cast<float>(options.warp_settled_px * options.warp_settled_px);
  const float max_shift_sq =
      static_cast<float>(options.warp_max_shift_px * options.warp_max_shift_px);
  for (size_t i = 0; i < points.size(); ++i) {
    if (!(*landed)[i]) continue;
    const cv::Matx22f& a = warp[i];
    // Where the warp moves the window's corners less than warp_min_px from where a shift puts
    // them, the pyramid's shifted window fits as well: the landing stands.
    const float corner =
        static_cast<float>(half) * std::max(std::abs(a(0, 0) - 1) + std::abs(a(0, 1)),
                                            std::abs(a(1, 0)) + std::abs(a(1, 1) - 1));
    if (corner < min_px) continue;
    const float det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
    if (!(std::abs(det) > 1e-3f)) continue;
    const cv::Matx22f inv(a(1, 1) / det, -a(0, 1) / det, -a(1, 0) / det, a(0, 0) / det);
    // The template: `from` sampled where each offset of the window (and its ring) comes from.
    // The map is affine: with the grid's four corners inside the image, all of it is.
    const float r = static_cast<float>(half + 1);
    const cv::Point2f& p = points[i];
    bool inside = true;
    for (const float cy : {-r, r})
      for (const float cx : {-r, r})
        inside = inside && Inside(from, p.x + inv(0, 0) * cx + inv(0, 1) * cy,
                                  p.y + inv(1, 0) * cx + inv(1, 1) * cy);
    if (!inside) continue;
    for (int gy = 0; gy < side; ++gy) {
      const float wy = static_cast<float>(gy) - r;
      float x = p.x - inv(0, 0) * r + inv(0, 1) * wy;
      float y = p.y - inv(1, 0) * r + inv(1, 1) * wy;
      float* row = templ.data() + gy * side;
      for (int gx = 0; gx < side; ++gx, x += inv(0, 0), y += inv(1, 0))
        row[gx] = Bilinear(from, x, y);
    }
    float hxx = 0, hxy = 0, hyy = 0;
    int k = 0;
    for (int gy = 1; gy < side - 1; ++gy)
      for (int gx = 1; gx < side - 1; ++gx, ++k) {
        const float* c = templ.data() + gy * side + gx;
        tx[k] = 0.5f * (c[1] - c[-1]);
        ty[k] = 0.5f * (c[side] - c[-side]);
        tv[k] = c[0];
        hxx += tx[k] * tx[k];
        hxy += tx[k] * ty[k];
        hyy += ty[k] * ty[k];
      }
    const float hdet = hxx * hyy - hxy * hxy;
    if (!(hdet > 1e-6f * (hxx + hyy) * (hxx + hyy))) continue;
    const cv::Point2f start = *(*landed)[i];
    cv::Point2f q = start;
    bool settled = false;
    for (int it = 0; it < options.warp_iterations; ++it) {
      if (!Inside(to, q.x - static_cast<float>(half), q.y - static_cast<float>(half)) ||
          !Inside(to, q.x + static_cast<float>(half), q.y + static_cast<float>(half)))
        break;
      // Every pixel of the window is at the same fraction of a pixel: one set of bilinear
      // weights for all of them.
      const int x0 = static_cast<int>(q.x) - half;
      const int y0 = static_cast<int>(q.y) - half;
      const float ax = q.x - static_cast<float>(static_cast<int>(q.x));
      const float ay = q.y - static_cast<float>(static_cast<int>(q.y));
      const float w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay,
                  w11 = ax * ay;
      for (int wy = 0; wy < width; ++wy) {
        const uchar* r0 = to.ptr<uchar>(y0 + wy) + x0;
        const uchar* r1 = r0 + to.step[0];
        float* e = err.data() + wy * width;
        const float* t = tv.data() + wy * width;
        for (int wx = 0; wx < width; ++wx)
          e[wx] = w00 * static_cast<float>(r0[wx]) + w01 * static_cast<float>(r0[wx + 1]) +
                  w10 * static_cast<float>(r1[wx]) + w11 * static_cast<float>(r1[wx + 1]) - t[wx];
      }
      // Eight partial sums (the padding is zero): the loop vectorizes.
      std::array<float, 8> sx{}, sy{};
      for (size_t j = 0; j < err.size(); j += 8)
        for (size_t l = 0; l < 8; ++l) {
          sx[l] += tx[j + l] * err[j + l];
          sy[l] += ty[j + l] * err[j + l];
        }
      float bx = 0, by = 0;
      for (size_t l = 0; l < 8; ++l) {
        bx += sx[l];
        by += sy[l];
      }
      const float dx = (hyy * bx - hxy * by) / hdet;
      const float dy = (hxx * by - hxy * bx) / hdet;
      q.x -= dx;
      q.y -= dy;
      if (dx * dx + dy * dy < settled_sq) {
        settled = true;
        break;
      }
    }
    const cv::Point2f moved = q - start;
    if (settled && moved.x * moved.x + moved.y * moved.y <= max_shift_sq) (*landed)[i] = q;
  }
}

}  // namespace rgbdvo
