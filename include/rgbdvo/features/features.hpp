#pragma once
// SIFT keypoints and descriptors on the grey colour image (paper section 3, Lowe 2004).

#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <string>
#include <vector>

namespace rgbdvo {

class Sift;  // features/sift/sift.hpp, private to the library

// kRgbdvo: rgbdvo's own SIFT (features/sift: OpenCV's detector and descriptor, about twice as
// fast); kOpenCv: cv::SIFT.
enum class SiftImplementation { kRgbdvo, kOpenCv };

struct FeatureOptions {
  SiftImplementation implementation = SiftImplementation::kRgbdvo;
  int max_features = 0;   // keep the N strongest, 0 = all (paper: all, 200-1500)
  int octave_layers = 3;  // SIFT scales per octave (Lowe: 3)
  // The scale space starts at the image's own resolution (upsample_first_octave false) with a
  // base blur of 1 pixel, the finest the pixel grid holds (the camera's own blur is about 0.5),
  // and a contrast threshold of 0.015 (Lowe's 0.04 counts for the 2x-upsampled image, whose
  // finest scales this scale space does not have): about as many inliers as Lowe's detector on
  // the 2x-upsampled image or more, at about half the CPU of a frame
  // (docs/decisions/0015-native-resolution-sift.md). Lowe() below is Lowe's (and OpenCV's)
  // detector.
  double contrast_threshold = 0.015;  // SIFT DoG contrast threshold (Lowe/OpenCV: 0.04)
  double edge_threshold = 10.0;       // SIFT edge response ratio (Lowe/OpenCV: 10)
  double sigma = 1.0;                 // SIFT base blur (Lowe/OpenCV: 1.6)
  // true: the first octave is the colour image upsampled 2x (Lowe's "double the image"; 4x the
  // pixels of the image itself), as OpenCV always does. false: about 4x less work; rgbdvo's
  // SIFT starts at the image's own resolution; OpenCV's is run on the image halved (area
  // average), so that its upsampled first octave is back at image resolution, and keypoints are
  // scaled back.
  bool upsample_first_octave = false;
  // Lowe's parameters: the 2x-upsampled first octave, base blur 1.6, contrast 0.04.
  static FeatureOptions Lowe();
  void Check() const;
};

struct Features {
  std::vector<cv::KeyPoint> keypoints;  // colour image pixels
  // CV_8U, one 128-d row per keypoint: SIFT's entries are whole numbers 0..255, so bytes hold
  // them exactly and L2 distances between them are exact in any arithmetic.
  cv::Mat descriptors;
  size_t size() const { return keypoints.size(); }
};

// Extract() may be called from several threads at once: each call borrows a Sift (with its
// reusable buffers) from a pool that grows to the number of concurrent callers.
class SiftExtractor {
 public:
  explicit SiftExtractor(const FeatureOptions& options);
  ~SiftExtractor();
  SiftExtractor(const SiftExtractor&) = delete;
  SiftExtractor& operator=(const SiftExtractor&) = delete;
  // `image` is CV_8UC3 (BGR) or CV_8UC1.
  Features Extract(const cv::Mat& image) const;
  const FeatureOptions& options() const { return options_; }

 private:
  FeatureOptions options_;
  cv::Ptr<cv::SIFT> opencv_;  // implementation kOpenCv
  mutable std::mutex mutex_;  // guards pool_
  mutable std::vector<std::unique_ptr<Sift>> pool_;
};

}  // namespace rgbdvo
