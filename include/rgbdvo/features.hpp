#pragma once
// SIFT keypoints and descriptors on the grey colour image (paper section 3, Lowe 2004).

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

namespace rgbdvo {

struct FeatureOptions {
  int max_features = 0;              // keep the N strongest, 0 = all (paper: all, 200-1500)
  int octave_layers = 3;             // SIFT scales per octave (Lowe: 3)
  double contrast_threshold = 0.04;  // SIFT DoG contrast threshold (Lowe/OpenCV: 0.04)
  double edge_threshold = 10.0;      // SIFT edge response ratio (Lowe/OpenCV: 10)
  double sigma = 1.6;                // SIFT base blur (Lowe/OpenCV: 1.6)
  // true: SIFT on the colour image, whose first octave OpenCV always upsamples 2x (Lowe's
  // "double the image"; 4x the pixels of the image itself). false: SIFT on the image halved
  // (area average), so the upsampled first octave is back at the image's own resolution;
  // keypoints are scaled back to image pixels. About 4x less work and fewer, larger-scale
  // features (none below 1.6 image pixels of blur, where Kinect colour is mostly noise).
  bool upsample_first_octave = true;
  void Check() const;
};

struct Features {
  std::vector<cv::KeyPoint> keypoints;  // colour image pixels
  cv::Mat descriptors;                  // CV_32F, one 128-d row per keypoint
  size_t size() const { return keypoints.size(); }
};

class SiftExtractor {
 public:
  explicit SiftExtractor(const FeatureOptions& options);
  // `image` is CV_8UC3 (BGR) or CV_8UC1.
  Features Extract(const cv::Mat& image) const;

 private:
  cv::Ptr<cv::SIFT> sift_;
  bool upsample_ = true;
};

}  // namespace rgbdvo
