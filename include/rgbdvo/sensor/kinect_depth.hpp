#pragma once
// Kinect v1 raw 11-bit disparity <-> metric Z-depth.
//
// The depth stream of a Kinect v1 (libfreenect FREENECT_DEPTH_11BIT) carries, per IR pixel, a
// raw disparity value d in [0, 2047]; 2047 means "no reading". We use the first-order inverse
// fit published by Nicolas Burrus (2011) and quoted on the OpenKinect wiki ("Imaging
// Information"):
//     z [m] = 1 / (d * -0.0030711016 + 3.3309495161)
// The fit is good to about 1 cm within 2.5 m and about 10 cm at 4 m (OpenKinect wiki). The
// denominator vanishes at d = 1084.6, so only d <= 1084 give a (positive) depth; larger values
// (and 2047) are treated as no reading. The resolution worsens with the square of the depth:
// one raw step is 0.0030711016 * z^2 m (1.2 cm at 2 m, 4.9 cm at 4 m).

#include <cstdint>
#include <opencv2/core.hpp>

namespace rgbdvo {

constexpr uint16_t kKinectNoReading = 2047;

// The Kinect v1's depth noise grows with the square of the depth: sigma_z = c z^2, with
// c = 1.425e-3 1/m (Khoshelham & Elberink 2012). The refinement, the depth fallback, the floor
// fit and the synthetic Kinect all use it.
constexpr double kKinectDepthNoiseCoeff = 1.425e-3;  // 1/m

// Z-depth in metres of one raw disparity value, 0 for no reading.
double MetresFromKinectRaw(uint16_t raw);

// The raw value whose depth is nearest to z_m (the inverse of MetresFromKinectRaw up to the
// raw quantisation), kKinectNoReading when z_m <= 0 or beyond the range of raw values.
uint16_t KinectRawFromMetres(double z_m);

// Whole images: CV_16UC1 raw disparity -> CV_32FC1 metres (0 = no reading), and back.
// Throws std::invalid_argument for the wrong image type.
cv::Mat DepthFromKinectRaw(const cv::Mat& raw);
cv::Mat KinectRawFromDepth(const cv::Mat& depth_m);

}  // namespace rgbdvo
