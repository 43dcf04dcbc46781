#pragma once
// SIFT keypoints and descriptors on the grey colour image (paper section 3, Lowe 2004).

#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <string>
#include <vector>

#include "rgbdvo/features/sift/sift.hpp"

namespace rgbdvo {

struct FeatureOptions {
  // "rgbdvo": rgbdvo's own SIFT (sift.hpp: OpenCV's detector and descriptor, about twice as
  // fast); "opencv": cv::SIFT.
  std::string implementation = "rgbdvo";
  int max_features = 0;              // keep the N strongest, 0 = all (paper: all, 200-1500)
  int octave_layers = 3;             // SIFT scales per octave (Lowe: 3)
  double contrast_threshold = 0.04;  // SIFT DoG contrast threshold (Lowe/OpenCV: 0.04)
  double edge_threshold = 10.0;      // SIFT edge response ratio (Lowe/OpenCV: 10)
  double sigma = 1.6;                // SIFT base blur (Lowe/OpenCV: 1.6)
  // true: the first octave is the colour image upsampled 2x (Lowe's "double the image"; 4x the
  // pixels of the image itself), as OpenCV always does. false: about 4x less work and fewer,
  // larger-scale features (none below 1.6 image pixels of blur): rgbdvo's SIFT starts at the
  // image's own resolution; OpenCV's is run on the image halved (area average), so that its
  // upsampled first octave is back at image resolution, and keypoints are scaled back.
  bool upsample_first_octave = true;
  void Check() const;
  SiftOptions ToSiftOptions() const;  // for implementation "rgbdvo"
};

struct Features {
  std::vector<cv::KeyPoint> keypoints;  // colour image pixels
  cv::Mat descriptors;                  // CV_32F, one 128-d row per keypoint
  size_t size() const { return keypoints.size(); }
};

// Extract() may be called from several threads at once: each call borrows a Sift (with its
// reusable buffers) from a pool that grows to the number of concurrent callers.
class SiftExtractor {
 public:
  explicit SiftExtractor(const FeatureOptions& options);
  // `image` is CV_8UC3 (BGR) or CV_8UC1.
  Features Extract(const cv::Mat& image) const;
  const FeatureOptions& options() const { return options_; }

 private:
  FeatureOptions options_;
  cv::Ptr<cv::SIFT> opencv_;  // implementation "opencv"
  mutable std::mutex mutex_;  // guards pool_
  mutable std::vector<std::unique_ptr<Sift>> pool_;
};

}  // namespace rgbdvo
