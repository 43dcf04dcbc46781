// The PNG decoder (ours, on ISA-L's inflate) as cv::imread would be asked: colour and
// unchanged, and the JPEG header reader. Each input is decoded as it is and with every chunk's
// CRC made right, so that mutations also reach the inflate, filter and sample code behind the
// CRC check.
#include <isa-l/crc.h>

#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "fuzz_input.hpp"
#include "rgbdvo/io/png_decoder.hpp"

namespace {

void Decode(const std::vector<uint8_t>& bytes) {
  for (const int flags : {cv::IMREAD_COLOR, cv::IMREAD_UNCHANGED}) {
    const rgbdvo::PngDecodeResult r = rgbdvo::DecodePng(bytes, flags);
    if (r.success && r.image.empty()) __builtin_trap();  // success means an image
  }
}

uint32_t BigEndian32(const uint8_t* p) {
  return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  rgbdvo::JpegSize(bytes);
  Decode(bytes);
  for (size_t pos = 8; pos + 12 <= bytes.size();) {
    const uint32_t len = BigEndian32(&bytes[pos]);
    if (len > bytes.size() - pos - 12) break;
    const uint32_t crc = crc32_gzip_refl(0, &bytes[pos + 4], len + 4);
    for (int k = 0; k < 4; ++k)
      bytes[pos + 8 + len + k] = static_cast<uint8_t>(crc >> (24 - 8 * k));
    pos += 12 + size_t{len};
  }
  Decode(bytes);
  return 0;
}
