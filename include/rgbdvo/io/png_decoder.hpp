#pragma once
// The image reader's own decoders (private to the library, not installed): PNG as cv::imread
// decodes it, and a JPEG's size read before decoding.

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rgbdvo/io/image_reader.hpp"

namespace rgbdvo {

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

}  // namespace rgbdvo
