#include "rgbdvo/features/features.hpp"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "rgbdvo/features/sift/sift.hpp"

namespace rgbdvo {

FeatureOptions FeatureOptions::Lowe() {
  FeatureOptions o;
  o.upsample_first_octave = true;
  o.sigma = 1.6;
  o.contrast_threshold = 0.04;
  return o;
}

void FeatureOptions::Check() const {
  if (max_features < 0)
    throw std::invalid_argument("FeatureOptions.max_features must be >= 0 (0 = all)");
  if (octave_layers < 1) throw std::invalid_argument("FeatureOptions.octave_layers must be >= 1");
  if (!(contrast_threshold > 0))
    throw std::invalid_argument("FeatureOptions.contrast_threshold must be > 0");
  if (!(edge_threshold > 0))
    throw std::invalid_argument("FeatureOptions.edge_threshold must be > 0");
  if (!(sigma > 0)) throw std::invalid_argument("FeatureOptions.sigma must be > 0");
}

namespace {

// The options of rgbdvo's own SIFT (implementation kRgbdvo).
SiftOptions ToSiftOptions(const FeatureOptions& o) {
  SiftOptions s;
  s.scale_space.octave_layers = o.octave_layers;
  s.scale_space.sigma = o.sigma;
  s.scale_space.upsample = o.upsample_first_octave;
  s.contrast_threshold = o.contrast_threshold;
  s.edge_threshold = o.edge_threshold;
  s.max_features = o.max_features;
  return s;
}

}  // namespace

SiftExtractor::SiftExtractor(const FeatureOptions& o) : options_(o) {
  o.Check();
  if (o.implementation == SiftImplementation::kOpenCv)
    opencv_ = cv::SIFT::create(o.max_features, o.octave_layers, o.contrast_threshold,
                               o.edge_threshold, o.sigma, CV_8U);
  else
    ToSiftOptions(o).Check();
}

SiftExtractor::~SiftExtractor() = default;

Features SiftExtractor::Extract(const cv::Mat& image) const {
  if (image.empty()) throw std::invalid_argument("SIFT: empty image");
  cv::Mat gray;
  if (image.channels() == 3)
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  else
    gray = image;
  Features f;
  if (!opencv_) {
    std::unique_ptr<Sift> sift;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!pool_.empty()) {
        sift = std::move(pool_.back());
        pool_.pop_back();
      }
    }
    if (!sift) sift = std::make_unique<Sift>(ToSiftOptions(options_));
    sift->DetectAndDescribe(gray, &f.keypoints, &f.descriptors);
    std::lock_guard<std::mutex> lock(mutex_);
    pool_.push_back(std::move(sift));
    return f;
  }
  if (options_.upsample_first_octave) {
    opencv_->detectAndCompute(gray, cv::noArray(), f.keypoints, f.descriptors);
    return f;
  }
  cv::Mat half;
  cv::resize(gray, half, cv::Size((gray.cols + 1) / 2, (gray.rows + 1) / 2), 0, 0, cv::INTER_AREA);
  opencv_->detectAndCompute(half, cv::noArray(), f.keypoints, f.descriptors);
  // Pixel centres: half-image pixel u covers image pixels 2u and 2u+1, centre 2u + 0.5.
  for (cv::KeyPoint& k : f.keypoints) {
    k.pt = cv::Point2f(2 * k.pt.x + 0.5f, 2 * k.pt.y + 0.5f);
    k.size *= 2;
  }
  return f;
}

}  // namespace rgbdvo
