#include "rgbdvo/sources/ros2_image.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "rgbdvo/io/opencv_codecs.hpp"
#include "rgbdvo/io/png_decoder.hpp"

namespace rgbdvo {
namespace {

constexpr size_t kCompressedDepthHeader = 12;  // i32 format, f32 a, f32 b

// A copy of the message's pixels as a matrix of `type` (bytes swapped from big-endian data),
// after checking that the data fills height x step with rows of width pixels.
cv::Mat Pixels(const Ros2Image& m, int type) {
  const size_t pixel = CV_ELEM_SIZE(type);
  if (m.width == 0 || m.height == 0) throw std::runtime_error("empty image");
  if (m.width > kMaxImageSide || m.height > kMaxImageSide)
    throw std::runtime_error(std::to_string(m.width) + "x" + std::to_string(m.height) +
                             " is larger than an image can be here");
  if (m.step < size_t{m.width} * pixel)
    throw std::runtime_error("step " + std::to_string(m.step) + " is shorter than a row of " +
                             std::to_string(m.width) + " pixels");
  if (m.data.size() / m.step < m.height)
    throw std::runtime_error("data has " + std::to_string(m.data.size()) + " bytes, " +
                             std::to_string(size_t{m.step} * m.height) + " expected");
  cv::Mat out(static_cast<int>(m.height), static_cast<int>(m.width), type);
  for (int y = 0; y < out.rows; ++y)
    std::memcpy(out.ptr(y), m.data.data() + size_t{m.step} * y, size_t{m.width} * pixel);
  const size_t channel = CV_ELEM_SIZE1(type);
  if (m.is_bigendian && channel > 1) {
    uint8_t* p = out.data;
    for (size_t i = 0; i + channel <= out.total() * pixel; i += channel)
      std::reverse(p + i, p + i + channel);
  }
  return out;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The image in PNG or JPEG bytes as cv::imdecode(flags) gives it: PNG by the library's own
// decoder where it can, else by OpenCV's.
cv::Mat Decode(const std::vector<uint8_t>& bytes, int flags, const std::string& what) {
  if (bytes.size() >= 8 && bytes[0] == 0x89 && bytes[1] == 'P') {
    const PngDecodeResult png = DecodePng(bytes, flags);
    if (png.success) return png.image;
    if (png.too_large || png.truncated)
      throw std::runtime_error(what + ": " + (png.too_large ? "too large" : "truncated PNG"));
  }
  if (const auto size = JpegSize(bytes.data(), bytes.size()))
    if (size->first > kMaxImageSide || size->second > kMaxImageSide)
      throw std::runtime_error(what + ": too large");
  cv::Mat image = ImdecodeWithOpenCv(bytes, flags, what);
  if (image.empty()) throw std::runtime_error(what + ": does not decode");
  return image;
}

}  // namespace

cv::Mat Ros2ColorImage(const Ros2Image& m) {
  static const std::map<std::string, std::pair<int, int>> kLayouts = {
      {"rgb8", {CV_8UC3, cv::COLOR_RGB2BGR}},   {"bgr8", {CV_8UC3, -1}},
      {"mono8", {CV_8UC1, cv::COLOR_GRAY2BGR}}, {"rgba8", {CV_8UC4, cv::COLOR_RGBA2BGR}},
      {"bgra8", {CV_8UC4, cv::COLOR_BGRA2BGR}},
  };
  const auto layout = kLayouts.find(m.encoding);
  if (layout == kLayouts.end())
    throw std::runtime_error("colour encoding '" + m.encoding +
                             "' not supported (rgb8, bgr8, mono8, rgba8, bgra8)");
  const auto [type, conversion] = layout->second;
  cv::Mat pixels = Pixels(m, type);
  if (conversion < 0) return pixels;
  cv::Mat bgr;
  cv::cvtColor(pixels, bgr, conversion);
  return bgr;
}

cv::Mat Ros2ColorImage(const Ros2CompressedImage& m) {
  const std::string format = Lower(m.format);
  if (format.find("compresseddepth") != std::string::npos ||
      (format.find("png") == std::string::npos && format.find("jpeg") == std::string::npos &&
       format.find("jpg") == std::string::npos))
    throw std::runtime_error("compressed colour format '" + m.format +
                             "' not supported (png, jpeg)");
  // Colour JPEG and PNG hold BGR order once decoded; a grey one is made BGR.
  return Decode(m.data, cv::IMREAD_COLOR, "compressed colour image");
}

cv::Mat Ros2DepthImage(const Ros2Image& m) {
  const bool mm = m.encoding == "16UC1" || m.encoding == "mono16";
  if (!mm && m.encoding != "32FC1")
    throw std::runtime_error("depth encoding '" + m.encoding +
                             "' not supported (16UC1 millimetres, 32FC1 metres)");
  cv::Mat depth;
  Pixels(m, mm ? CV_16UC1 : CV_32FC1).convertTo(depth, CV_32F, mm ? 1e-3 : 1.0);
  cv::patchNaNs(depth, 0);
  depth.setTo(0, depth < 0);
  return depth;
}

cv::Mat Ros2DepthImage(const Ros2CompressedImage& m) {
  const std::string format = Lower(m.format);
  const std::string encoding = m.format.substr(0, m.format.find(';'));
  if (format.find("compresseddepth") == std::string::npos ||
      format.find("rvl") != std::string::npos)
    throw std::runtime_error("compressed depth format '" + m.format +
                             "' not supported (image_transport compressedDepth png)");
  const bool mm = encoding == "16UC1" || encoding == "mono16";
  if (!mm && encoding != "32FC1")
    throw std::runtime_error("compressed depth encoding '" + encoding +
                             "' not supported (16UC1 millimetres, 32FC1 metres)");
  if (m.data.size() < kCompressedDepthHeader)
    throw std::runtime_error("compressedDepth data has " + std::to_string(m.data.size()) +
                             " bytes, shorter than its 12-byte header");
  float quant[2] = {0, 0};
  std::memcpy(quant, m.data.data() + 4, sizeof quant);
  const std::vector<uint8_t> png(m.data.begin() + kCompressedDepthHeader, m.data.end());
  const cv::Mat raw = Decode(png, cv::IMREAD_UNCHANGED, "compressedDepth PNG");
  if (raw.type() != CV_16UC1) throw std::runtime_error("compressedDepth PNG is not 16-bit grey");
  cv::Mat depth(raw.size(), CV_32FC1);
  if (mm) {
    raw.convertTo(depth, CV_32F, 1e-3);
    return depth;
  }
  // Quantised inverse depth: 0 is no reading.
  for (int y = 0; y < raw.rows; ++y)
    for (int x = 0; x < raw.cols; ++x) {
      const uint16_t v = raw.at<uint16_t>(y, x);
      const float z = v == 0 ? 0.0f : quant[0] / (static_cast<float>(v) - quant[1]);
      depth.at<float>(y, x) = std::isfinite(z) && z > 0 ? z : 0.0f;
    }
  return depth;
}

}  // namespace rgbdvo
