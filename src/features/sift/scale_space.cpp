#include "rgbdvo/features/sift/scale_space.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "rgbdvo/features/sift/gaussian_blur.hpp"

namespace rgbdvo {
namespace {

constexpr double kInitialBlur = 0.5;  // assumed blur of the camera image, pixels (Lowe 2004)
// Octaves continue while both sides have at least this many pixels (below, the 5-pixel border
// of the extrema search leaves almost nothing; OpenCV stops at about the same size).
constexpr int kMinSide = 12;

// Blurs src into dst (no overlap) with a Gaussian cut at kernel_sigmas * sigma; also writes
// dst - src into `difference` when given.
void Blur(const cv::Mat& src, cv::Mat& dst, double sigma, double kernel_sigmas,
          cv::Mat* difference = nullptr) {
  const int radius = std::max(1, static_cast<int>(std::ceil(kernel_sigmas * sigma)));
  GaussianBlur32f(src, dst, sigma, radius, difference);
}

}  // namespace

void ScaleSpaceOptions::Check() const {
  if (octave_layers < 1)
    throw std::invalid_argument("ScaleSpaceOptions.octave_layers must be >= 1");
  if (!(sigma > kInitialBlur)) throw std::invalid_argument("ScaleSpaceOptions.sigma must be > 0.5");
  if (!(kernel_sigmas >= 2))
    throw std::invalid_argument("ScaleSpaceOptions.kernel_sigmas must be >= 2");
}

ScaleSpace::ScaleSpace(const ScaleSpaceOptions& options) : options_(options) {
  options_.Check();
  // Level i has blur sigma * k^i, k = 2^(1/S); level i is level i - 1 blurred by the
  // difference in quadrature.
  const int S = options_.octave_layers;
  const double k = std::pow(2.0, 1.0 / S);
  level_sigmas_.assign(S + 3, 0.0);
  for (int i = 1; i < S + 3; ++i) {
    const double before = options_.sigma * std::pow(k, i - 1), after = before * k;
    level_sigmas_[i] = std::sqrt(after * after - before * before);
  }
}

bool ScaleSpace::Begin(const cv::Mat& gray) {
  if (gray.type() != CV_8UC1) throw std::invalid_argument("ScaleSpace: image must be CV_8UC1");
  const int up = options_.upsample ? 2 : 1;
  const int rows = gray.rows * up, cols = gray.cols * up;
  octaves_.clear();
  if (std::min(rows, cols) < kMinSide) return false;
  // Room for every octave's 2S + 5 planes: the octaves halve while both sides keep kMinSide.
  const size_t planes = 2 * static_cast<size_t>(options_.octave_layers) + 5;
  size_t total = 0;
  for (int r = rows, c = cols; std::min(r, c) >= kMinSide; r /= 2, c /= 2)
    total += planes * static_cast<size_t>(r) * c;
  if (total > storage_.size()) storage_ = HugePageBuffer(total);

  cv::Mat level0(rows, cols, CV_32F, storage_.data());
  gray.convertTo(scratch_, CV_32F);
  // The camera image has blur 0.5 (1 in the upsampled image); add what reaches sigma.
  const double have = kInitialBlur * up;
  const double add = std::sqrt(std::max(options_.sigma * options_.sigma - have * have, 0.01));
  if (options_.upsample) {
    cv::resize(scratch_, base_, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);
    Blur(base_, level0, add, options_.kernel_sigmas);
  } else {
    Blur(scratch_, level0, add, options_.kernel_sigmas);
  }
  Build(options_.upsample ? -1 : 0, 0, rows, cols);
  return true;
}

bool ScaleSpace::Next() {
  const cv::Mat& from = octave().gauss[options_.octave_layers];  // blur 2 sigma: sigma at half size
  const int rows = from.rows / 2, cols = from.cols / 2;
  if (std::min(rows, cols) < kMinSide) return false;
  cv::Mat level0(rows, cols, CV_32F, storage_.data() + next_offset_);
  for (int y = 0; y < rows; ++y) {
    const float* src = from.ptr<float>(2 * y);
    float* dst = level0.ptr<float>(y);
    for (int x = 0; x < cols; ++x) dst[x] = src[2 * x];
  }
  Build(octave().index + 1, next_offset_, rows, cols);
  return true;
}

void ScaleSpace::Build(int index, size_t offset, int rows, int cols) {
  const int S = options_.octave_layers;
  const size_t plane = static_cast<size_t>(rows) * cols;
  Octave o;
  o.index = index;
  o.shift = options_.upsample ? 0.25 : 0.0;
  float* at = storage_.data() + offset;
  o.gauss.resize(S + 3);
  o.dog.resize(S + 2);
  for (int i = 0; i < S + 3; ++i) o.gauss[i] = cv::Mat(rows, cols, CV_32F, at + i * plane);
  for (int i = 0; i < S + 2; ++i) o.dog[i] = cv::Mat(rows, cols, CV_32F, at + (S + 3 + i) * plane);
  for (int i = 1; i < S + 3; ++i)
    Blur(o.gauss[i - 1], o.gauss[i], level_sigmas_[i], options_.kernel_sigmas, &o.dog[i - 1]);
  next_offset_ = offset + (2 * static_cast<size_t>(S) + 5) * plane;
  octaves_.push_back(std::move(o));
}

}  // namespace rgbdvo
