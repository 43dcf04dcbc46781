#include "rgbdvo/sensor/kinect_depth.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace rgbdvo;

TEST_CASE("Kinect raw disparity follows Burrus's fit and 2047 means no reading") {
  CHECK(MetresFromKinectRaw(0) == Approx(1.0 / 3.3309495161));
  CHECK(MetresFromKinectRaw(759) == Approx(1.0 / (759 * -0.0030711016 + 3.3309495161)));
  CHECK(MetresFromKinectRaw(759) == Approx(1.0).margin(0.001));  // about 1 m
  CHECK(MetresFromKinectRaw(kKinectNoReading) == 0.0);
  CHECK(MetresFromKinectRaw(1085) == 0.0);  // beyond the pole of the fit
  CHECK(MetresFromKinectRaw(1084) > 100.0);
  // Depth grows with disparity.
  for (uint16_t raw = 1; raw <= 1084; ++raw)
    REQUIRE(MetresFromKinectRaw(raw) > MetresFromKinectRaw(raw - 1));
}

TEST_CASE("KinectRawFromMetres inverts the fit to within half a raw step") {
  for (int k = 0; 0.4 + 0.0137 * k < 8.0; ++k) {
    const double z = 0.4 + 0.0137 * k;
    const uint16_t raw = KinectRawFromMetres(z);
    REQUIRE(raw != kKinectNoReading);
    const double step = 0.0030711016 * z * z;  // dz/draw
    CHECK(std::abs(MetresFromKinectRaw(raw) - z) <= 0.5 * step * 1.05 + 1e-9);
  }
  CHECK(KinectRawFromMetres(0.0) == kKinectNoReading);
  CHECK(KinectRawFromMetres(-1.0) == kKinectNoReading);
  CHECK(KinectRawFromMetres(0.2) == kKinectNoReading);  // nearer than raw 0 can say
  CHECK(KinectRawFromMetres(NAN) == kKinectNoReading);
}

TEST_CASE("Kinect depth images convert both ways and keep missing readings missing") {
  cv::Mat depth(2, 3, CV_32FC1);
  depth.at<float>(0, 0) = 0.0f;
  depth.at<float>(0, 1) = 1.0f;
  depth.at<float>(0, 2) = 2.5f;
  depth.at<float>(1, 0) = 4.0f;
  depth.at<float>(1, 1) = -1.0f;
  depth.at<float>(1, 2) = 0.6f;
  const cv::Mat raw = KinectRawFromDepth(depth);
  REQUIRE(raw.type() == CV_16UC1);
  CHECK(raw.at<uint16_t>(0, 0) == kKinectNoReading);
  CHECK(raw.at<uint16_t>(1, 1) == kKinectNoReading);
  const cv::Mat back = DepthFromKinectRaw(raw);
  REQUIRE(back.type() == CV_32FC1);
  CHECK(back.at<float>(0, 0) == 0.0f);
  CHECK(back.at<float>(1, 1) == 0.0f);
  CHECK(back.at<float>(0, 1) == Approx(1.0).margin(0.002));
  CHECK(back.at<float>(0, 2) == Approx(2.5).margin(0.01));
  CHECK(back.at<float>(1, 0) == Approx(4.0).margin(0.025));
  CHECK(back.at<float>(1, 2) == Approx(0.6).margin(0.001));
  CHECK_THROWS_AS(DepthFromKinectRaw(cv::Mat(2, 2, CV_32FC1)), std::invalid_argument);
  CHECK_THROWS_AS(KinectRawFromDepth(cv::Mat(2, 2, CV_16UC1)), std::invalid_argument);
}
