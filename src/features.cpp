#include "rgbdvo/features.hpp"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace rgbdvo {

void FeatureOptions::Check() const {
  if (max_features < 0) throw std::invalid_argument("max_features must be >= 0 (0 = all)");
  if (octave_layers < 1) throw std::invalid_argument("octave_layers must be >= 1");
  if (!(contrast_threshold > 0)) throw std::invalid_argument("contrast_threshold must be > 0");
  if (!(edge_threshold > 0)) throw std::invalid_argument("edge_threshold must be > 0");
  if (!(sigma > 0)) throw std::invalid_argument("sigma must be > 0");
}

SiftExtractor::SiftExtractor(const FeatureOptions& o)
    : sift_(cv::SIFT::create(o.max_features, o.octave_layers, o.contrast_threshold,
                             o.edge_threshold, o.sigma)),
      upsample_(o.upsample_first_octave) {
  o.Check();
}

Features SiftExtractor::Extract(const cv::Mat& image) const {
  cv::Mat gray;
  if (image.channels() == 3)
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  else
    gray = image;
  Features f;
  if (upsample_) {
    sift_->detectAndCompute(gray, cv::noArray(), f.keypoints, f.descriptors);
    return f;
  }
  cv::Mat half;
  cv::resize(gray, half, cv::Size((gray.cols + 1) / 2, (gray.rows + 1) / 2), 0, 0, cv::INTER_AREA);
  sift_->detectAndCompute(half, cv::noArray(), f.keypoints, f.descriptors);
  // Pixel centres: half-image pixel u covers image pixels 2u and 2u+1, centre 2u + 0.5.
  for (cv::KeyPoint& k : f.keypoints) {
    k.pt = cv::Point2f(2 * k.pt.x + 0.5f, 2 * k.pt.y + 0.5f);
    k.size *= 2;
  }
  return f;
}

}  // namespace rgbdvo
