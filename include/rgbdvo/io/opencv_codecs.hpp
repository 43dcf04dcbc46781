#pragma once
// OpenCV's image codecs (cv::imread, cv::imwrite), loaded when first needed. Linked, they pull
// about 130 shared libraries into the process (GDAL, GDCM, OpenEXR, libheif, ...), whose loading
// took about 70 ms of CPU at every start, as much as 3-4 frames of odometry; the PNGs of a
// recording are decoded by ReadImage's own decoder, so most runs never need them.

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace rgbdvo {

// cv::imread(path, flags). Throws std::runtime_error naming `path` when OpenCV's codec library
// cannot be loaded.
cv::Mat ImreadWithOpenCv(const std::string& path, int imread_flags);

// cv::imwrite(path, image): false when OpenCV cannot write it. Throws std::runtime_error naming
// `path` when OpenCV's codec library cannot be loaded.
bool ImwriteWithOpenCv(const std::string& path, const cv::Mat& image);

// cv::imdecode(bytes, flags): an empty image when OpenCV cannot decode them. Throws
// std::runtime_error naming `what` (the message holding the bytes) when OpenCV's codec library
// cannot be loaded.
cv::Mat ImdecodeWithOpenCv(const std::vector<uint8_t>& bytes, int imread_flags,
                           const std::string& what);

}  // namespace rgbdvo
