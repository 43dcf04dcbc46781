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

struct PngDecodeResult {
  bool success = false;    // false: not decoded here (`reason`); cv::imread decides
  bool too_large = false;  // the header claims more than kMaxImageSide: not for cv::imread either
  // The file ends inside a chunk (a copy or a recording cut short): no image, as cv::imread finds
  // too, which would also print libpng's "Read Error" line.
  bool truncated = false;
  std::string reason;  // why not, e.g. "interlaced", "IDAT CRC mismatch"
  cv::Mat image;       // on success: what cv::imread(path, flags) returns
};

// Decodes the bytes of a PNG file as cv::imread(path, flags) would for flags cv::IMREAD_COLOR
// or cv::IMREAD_UNCHANGED. Handled: non-interlaced, bit depth 8 with colour type 2 (RGB) or 6
// (RGBA), and, for IMREAD_UNCHANGED only, grey (type 0) of bit depth 8 or 16. Every chunk's
// CRC (libpng rejects critical chunks with a bad CRC; ISA-L's CRC-32 costs little), the
// zlib stream's Adler-32 and its exact length are checked; anything unsupported, suspicious or
// corrupt is a success=false result, never an exception, and left to cv::imread to judge.
PngDecodeResult DecodePng(const uint8_t* bytes, size_t size, int imread_flags);
PngDecodeResult DecodePng(const std::vector<uint8_t>& bytes, int imread_flags);

// Width and height from a JPEG's frame header (SOF0-SOF15), nullopt when `bytes` is no JPEG or
// has none before its scan data.
std::optional<std::pair<uint32_t, uint32_t>> JpegSize(const uint8_t* bytes, size_t size);
std::optional<std::pair<uint32_t, uint32_t>> JpegSize(const std::vector<uint8_t>& bytes);

// cv::imread(path, flags) with DecodePng for the PNGs it handles: the same image, empty when the
// file is missing, corrupt or truncated (a PNG cut short is not passed on to cv::imread, which
// would print a line of its own; other corrupt files are, and it has the last word). Throws
// std::runtime_error naming the file and the limit for a file above kMaxImageFileBytes or a PNG
// or JPEG claiming more than kMaxImageSide pixels a side (other formats: OpenCV's own limit).
cv::Mat ReadImage(const std::string& path, int imread_flags);

}  // namespace rgbdvo
