#pragma once
// SIFT keypoints and descriptors (Lowe, "Distinctive Image Features from Scale-Invariant
// Keypoints", IJCV 2004): rgbdvo's own implementation of the detector and descriptor of OpenCV's
// cv::SIFT (same parameters, same keypoint conventions, same descriptor layout), built to run
// at camera rate: scale-space buffers reused between images, the 26-neighbour extremum test
// as running 3x3 maxima and minima over whole rows, and descriptors sampled on a fixed grid.

#include <cstdint>
#include <opencv2/core.hpp>
#include <unordered_set>
#include <utility>
#include <vector>

#include "rgbdvo/features/sift/scale_space.hpp"

namespace rgbdvo {

struct SiftOptions {
  ScaleSpaceOptions scale_space;     // octave_layers, sigma, upsample (Lowe's octave -1)
  double contrast_threshold = 0.04;  // |DoG| at the extremum, x S / 255 (Lowe/OpenCV: 0.04)
  double edge_threshold = 10.0;      // principal curvature ratio r (Lowe section 4.1: 10)
  // Keep the N largest responses, 0 = all. Only those N get orientations and descriptors (most
  // of a keypoint's cost), so a limit also bounds the time a frame takes.
  int max_features = 0;
  void Check() const;
};

// A DoG extremum after sub-pixel refinement, in octave pixels.
struct Extremum {
  int layer = 0, x = 0, y = 0;   // integer position of the refined extremum
  float dx = 0, dy = 0, ds = 0;  // sub-pixel offsets (|.| < 0.5)
  float response = 0;            // |DoG| interpolated at the extremum, grey levels / 255
};

class Sift {
 public:
  explicit Sift(const SiftOptions& options);
  // Keypoints in image pixels (cv::KeyPoint: pt, size = 2 x scale sigma, angle in degrees
  // clockwise, response = |DoG| at the extremum / 255, octave packed as OpenCV packs it) and
  // one CV_8U row of 128 values per keypoint. `gray` is CV_8UC1. Not thread-safe: it
  // reuses its buffers; use one Sift per thread.
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors);

 private:
  // A keypoint found, before its descriptor: where to compute it.
  struct Found {
    int octave;  // index in the scale space's octaves()
    int layer;
    float x, y, scale;  // octave pixels
  };
  // Appends the extrema of octave `index` to extrema_.
  void SearchOctave(int index);
  // Orientations (Lowe section 5): a keypoint for each peak, appended to keypoints and found_.
  void Orient(int octave, const Extremum& e, std::vector<cv::KeyPoint>* keypoints);
  // With max_features: orients the strongest extrema and keeps the strongest keypoints.
  void OrientStrongest(std::vector<cv::KeyPoint>* keypoints);

  SiftOptions options_;
  ScaleSpace scale_space_;
  std::vector<float> row_buffers_;                 // running maxima/minima of the extremum search
  std::vector<uint8_t> flags_;                     // extremum candidates of one row
  std::unordered_set<int64_t> refined_;            // refined extrema of the octave (layer, y, x)
  std::vector<std::pair<int, Extremum>> extrema_;  // of the image, with their octave's index
  std::vector<Found> found_;  // one per keypoint, in the order of the keypoints
};

}  // namespace rgbdvo
