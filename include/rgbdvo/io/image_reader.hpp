#pragma once
// PNG decoding for the kinds of PNG the TUM RGB-D benchmark stores (8-bit RGB colour, 16-bit
// grey depth), about 2.5x as fast as cv::imread (libpng + zlib). Inflate and CRC-32 are Intel
// ISA-L's; chunk parsing, unfiltering (PNG spec 1.2 section 6) and the sample order are ours.
// Anything else goes to cv::imread (OpenCV's codecs, loaded when first needed), so the result
// is always cv::imread's (a PNG cut short gives no image, as there, without OpenCV's libpng
// printing a line of its own).

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rgbdvo {

// The largest image read, pixels a side: above every RGB-D sensor's (Kinect v1 colour 1280x1024,
// Kinect v2 1920x1080, Azure Kinect 4096x3072). A file claiming more is refused before anything
// of that size is allocated.
constexpr uint32_t kMaxImageSide = 4096;
// The largest image file read: 4096x4096 pixels of 16-bit RGBA, stored uncompressed.
constexpr long kMaxImageFileBytes = 4096L * 4096 * 8 + (1L << 20);

// cv::imread(path, flags) with DecodePng for the PNGs it handles: the same image, empty when the
// file is missing, corrupt or truncated (a PNG cut short is not passed on to cv::imread, which
// would print a line of its own; other corrupt files are, and it has the last word). Throws
// std::runtime_error naming the file and the limit for a file above kMaxImageFileBytes or a PNG
// or JPEG claiming more than kMaxImageSide pixels a side (other formats: OpenCV's own limit).
cv::Mat ReadImage(const std::string& path, int imread_flags);

}  // namespace rgbdvo
