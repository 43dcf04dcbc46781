// Pixels of ROS 2 image messages: colour layouts, depth scales and byte orders, PNG and JPEG,
// image_transport's compressedDepth, and the refusals.
#include "rgbdvo/sources/ros2_image.hpp"

#include <catch2/catch.hpp>
#include <cstring>
#include <functional>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

using namespace rgbdvo;

namespace {

Ros2Image Message(const cv::Mat& pixels, const std::string& encoding) {
  Ros2Image m;
  m.height = pixels.rows, m.width = pixels.cols, m.encoding = encoding;
  m.step = static_cast<uint32_t>(pixels.cols * pixels.elemSize());
  m.data.assign(pixels.datastart, pixels.dataend);
  return m;
}

std::string RefusalOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// image_transport's compressedDepth: i32 format, f32 a, f32 b, then the PNG.
Ros2CompressedImage CompressedDepth(const cv::Mat& raw16, const std::string& encoding, float a,
                                    float b) {
  Ros2CompressedImage m;
  m.format = encoding + "; compressedDepth png";
  m.data.assign(12, 0);
  std::memcpy(m.data.data() + 4, &a, 4);
  std::memcpy(m.data.data() + 8, &b, 4);
  std::vector<uint8_t> png;
  cv::imencode(".png", raw16, png);
  m.data.insert(m.data.end(), png.begin(), png.end());
  return m;
}

}  // namespace

TEST_CASE("ROS 2 colour images: rgb8, bgr8, mono8 and padded rows give the same BGR") {
  cv::Mat bgr(4, 5, CV_8UC3);
  cv::randu(bgr, 0, 255);
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  CHECK(cv::norm(Ros2ColorImage(Message(rgb, "rgb8")), bgr, cv::NORM_INF) == 0);
  CHECK(cv::norm(Ros2ColorImage(Message(bgr, "bgr8")), bgr, cv::NORM_INF) == 0);
  Ros2Image padded = Message(bgr, "bgr8");
  padded.step = 16;
  padded.data.clear();
  for (int y = 0; y < 4; ++y) {
    padded.data.insert(padded.data.end(), bgr.ptr(y), bgr.ptr(y) + 15);
    padded.data.push_back(0);
  }
  CHECK(cv::norm(Ros2ColorImage(padded), bgr, cv::NORM_INF) == 0);
  cv::Mat grey(4, 5, CV_8UC1, cv::Scalar(7));
  CHECK(Ros2ColorImage(Message(grey, "mono8")).at<cv::Vec3b>(2, 2) == cv::Vec3b(7, 7, 7));
}

TEST_CASE("ROS 2 depth images: 16UC1 millimetres, 32FC1 metres, either byte order") {
  cv::Mat mm(2, 3, CV_16UC1);
  mm = cv::Scalar(1500);
  mm.at<uint16_t>(0, 0) = 0;
  const cv::Mat m = Ros2DepthImage(Message(mm, "16UC1"));
  CHECK(m.at<float>(1, 1) == Approx(1.5f));
  CHECK(m.at<float>(0, 0) == 0);
  Ros2Image big = Message(mm, "16UC1");
  big.is_bigendian = 1;
  for (size_t i = 0; i + 1 < big.data.size(); i += 2) std::swap(big.data[i], big.data[i + 1]);
  CHECK(cv::norm(Ros2DepthImage(big), m, cv::NORM_INF) == 0);
  cv::Mat metres(2, 3, CV_32FC1, cv::Scalar(2.25f));
  metres.at<float>(0, 1) = std::numeric_limits<float>::quiet_NaN();
  metres.at<float>(0, 2) = -1;
  const cv::Mat f = Ros2DepthImage(Message(metres, "32FC1"));
  CHECK(f.at<float>(1, 2) == 2.25f);
  CHECK(f.at<float>(0, 1) == 0);
  CHECK(f.at<float>(0, 2) == 0);
}

TEST_CASE("ROS 2 compressed images: PNG and JPEG colour, compressedDepth 16UC1 and 32FC1") {
  cv::Mat bgr(16, 16, CV_8UC3, cv::Scalar(10, 120, 230));
  std::vector<uint8_t> png, jpeg;
  cv::imencode(".png", bgr, png);
  cv::imencode(".jpg", bgr, jpeg);
  Ros2CompressedImage c;
  c.format = "png";
  c.data = png;
  CHECK(cv::norm(Ros2ColorImage(c), bgr, cv::NORM_INF) == 0);
  c.format = "rgb8; jpeg compressed bgr8";
  c.data = jpeg;
  CHECK(cv::norm(Ros2ColorImage(c), bgr, cv::NORM_INF) <= 3);

  cv::Mat mm(4, 4, CV_16UC1, cv::Scalar(1234));
  mm.at<uint16_t>(1, 1) = 0;
  const cv::Mat d16 = Ros2DepthImage(CompressedDepth(mm, "16UC1", 0, 0));
  CHECK(d16.at<float>(0, 0) == Approx(1.234f));
  CHECK(d16.at<float>(1, 1) == 0);
  // Inverse depth: value v is a / (v - b) metres.
  cv::Mat inv(4, 4, CV_16UC1, cv::Scalar(1100));
  inv.at<uint16_t>(2, 2) = 0;
  const cv::Mat d32 = Ros2DepthImage(CompressedDepth(inv, "32FC1", 2000.0f, 100.0f));
  CHECK(d32.at<float>(0, 0) == Approx(2.0f));
  CHECK(d32.at<float>(2, 2) == 0);
}

TEST_CASE("ROS 2 images refused with the reason: encoding, short data, formats") {
  cv::Mat bgr(4, 5, CV_8UC3, cv::Scalar(1, 2, 3));
  Ros2Image yuv = Message(bgr, "yuv422");
  CHECK_THAT(RefusalOf([&] { Ros2ColorImage(yuv); }), Catch::Contains("yuv422"));
  Ros2Image shorter = Message(bgr, "bgr8");
  shorter.data.resize(shorter.data.size() / 2);
  CHECK_THAT(RefusalOf([&] { Ros2ColorImage(shorter); }), Catch::Contains("bytes"));
  Ros2Image narrow = Message(bgr, "bgr8");
  narrow.step = 3;
  CHECK_THAT(RefusalOf([&] { Ros2ColorImage(narrow); }), Catch::Contains("step"));
  CHECK_THAT(RefusalOf([&] { Ros2DepthImage(Message(bgr, "rgb8")); }), Catch::Contains("rgb8"));
  Ros2CompressedImage c;
  c.format = "16UC1; compressedDepth png";
  c.data = {1, 2, 3};
  CHECK_THAT(RefusalOf([&] { Ros2DepthImage(c); }), Catch::Contains("12-byte header"));
  c.format = "jpeg";
  CHECK_THAT(RefusalOf([&] { Ros2DepthImage(c); }), Catch::Contains("jpeg"));
  CHECK_THAT(RefusalOf([&] { Ros2ColorImage(c); }), Catch::Contains("does not decode"));
}
