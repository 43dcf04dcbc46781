#pragma once
// The Gaussian and difference-of-Gaussian scale space of SIFT (Lowe 2004, section 3), built one
// octave at a time into buffers that are reused from image to image. Every octave of an image
// stays until the next image (a third more memory than the first octave alone), so that
// keypoints can be described after all octaves are searched.

#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "rgbdvo/util/huge_page_buffer.hpp"

namespace rgbdvo {

struct ScaleSpaceOptions {
  int octave_layers = 3;  // S: scales per octave at which extrema are sought (Lowe: 3)
  double sigma = 1.6;     // blur of each octave's first level, in that octave's pixels (Lowe: 1.6)
  // true: the first octave has twice the image's resolution (Lowe's "double the image", the
  // octave -1 of OpenCV's SIFT); false: it has the image's own resolution.
  bool upsample = true;
  // Gaussian kernels are cut at this many sigmas (OpenCV's SIFT: 4). The weight beyond 3 sigma
  // is 0.27%, a quarter of the work: measured over 5 RANSAC seeds on fr1_xyz and fr3_teddy, 3
  // was as accurate as 4.
  double kernel_sigmas = 3.0;
  void Check() const;
};

// One octave: S + 3 Gaussian levels and S + 2 differences, CV_32F, grey values 0..255.
struct Octave {
  int index = 0;  // -1 for the upsampled octave; pixel size is 2^index image pixels
  std::vector<cv::Mat> gauss;
  std::vector<cv::Mat> dog;  // dog[i] = gauss[i + 1] - gauss[i]
  // Image pixel coordinate of octave pixel coordinate x (the same for y): x * 2^index - shift.
  // The 2x upsampling puts upsampled pixel x at image coordinate x / 2 - 1/4 (shift 1/4, which
  // decimation keeps, since it keeps every second pixel starting at 0); without it, shift 0.
  double ToImage(double x) const { return std::ldexp(x, index) - shift; }
  double shift = 0;
};

class ScaleSpace {
 public:
  explicit ScaleSpace(const ScaleSpaceOptions& options);
  // Starts on a CV_8UC1 image: builds the first octave. False when the image is too small.
  bool Begin(const cv::Mat& gray);
  // Builds the next octave (half the size) from the current one; false when it would be too small.
  bool Next();
  const Octave& octave() const { return octaves_.back(); }  // the one built last
  // Every octave built since Begin, the first one first.
  const std::vector<Octave>& octaves() const { return octaves_; }

 private:
  // Appends the octave whose level 0 (already blurred to sigma) is at storage_[offset].
  void Build(int index, size_t offset, int rows, int cols);
  ScaleSpaceOptions options_;
  std::vector<double> level_sigmas_;  // incremental blur from level i - 1 to level i
  // Every level of every octave, reused from image to image; not zeroed (every level is written
  // before it is read).
  HugePageBuffer storage_;
  size_t next_offset_ = 0;  // where in storage_ the next octave goes
  cv::Mat base_, scratch_;
  std::vector<Octave> octaves_;
};

}  // namespace rgbdvo
