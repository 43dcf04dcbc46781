#pragma once
// Separable Gaussian blur of float images for the SIFT scale space: one pass over the image
// that keeps the horizontally blurred rows in a small ring buffer (cache-resident) and can write
// the difference dst - src (the scale space's difference of Gaussians) in the same pass.

#include <opencv2/core.hpp>

namespace rgbdvo {

// dst = src blurred by a Gaussian of `sigma` pixels cut at `radius` pixels (normalised sampled
// kernel, borders reflected without repeating the edge pixel, as OpenCV's BORDER_REFLECT_101).
// src and dst are CV_32FC1 of the same size and must not overlap. If `difference` is not null,
// it receives dst - src (same size, CV_32FC1). Matches cv::GaussianBlur with
// ksize = 2 * radius + 1 to float rounding.
void GaussianBlur32f(const cv::Mat& src, cv::Mat& dst, double sigma, int radius,
                     cv::Mat* difference = nullptr);

}  // namespace rgbdvo
