#include "rgbdvo/io/image_reader.hpp"

#include <isa-l/crc.h>
#include <isa-l/igzip_lib.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <opencv2/imgcodecs.hpp>  // the IMREAD_ flags
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "rgbdvo/io/opencv_codecs.hpp"
#include "rgbdvo/io/png_decoder.hpp"
#include "rgbdvo/util/input_file.hpp"
#include "rgbdvo/util/simd.hpp"

namespace rgbdvo {
namespace {

uint32_t BigEndian32(const uint8_t* p) {
  return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3];
}

PngDecodeResult Fail(const char* why) {
  PngDecodeResult r;
  r.reason = why;
  return r;
}

// The Sub filter over whole 16-byte vectors (12 for 3-byte pixels) as a prefix sum: adding the
// vector shifted by bpp, 2 bpp, 4 bpp, ... bytes sums each byte with all pixels to its left in the
// vector; the last pixel of the previous vector is then added to every pixel. Returns how many
// bytes it did; reads up to 4 bytes past them (the buffer is padded).
template <int kBpp>
size_t SubVector(uint8_t* row, size_t n) {
#if defined(__SSE2__)
  if constexpr (kBpp >= 2) {
    constexpr size_t kStep = kBpp == 3 ? 12 : 16;
    __m128i last = _mm_setzero_si128();
    size_t i = 0;
    for (; i + kStep <= n; i += kStep) {
      __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i));
      x = _mm_add_epi8(x, _mm_slli_si128(x, kBpp));
      x = _mm_add_epi8(x, _mm_slli_si128(x, 2 * kBpp));
      if constexpr (kBpp == 2) x = _mm_add_epi8(x, _mm_slli_si128(x, 4 * kBpp));
      x = _mm_add_epi8(x, last);
      if constexpr (kBpp == 3) {
        _mm_storel_epi64(reinterpret_cast<__m128i*>(row + i), x);
        const int tail = _mm_cvtsi128_si32(_mm_srli_si128(x, 8));
        std::memcpy(row + i + 8, &tail, 4);
        last = _mm_srli_si128(_mm_slli_si128(x, 4), 13);  // bytes 9-11 to 0-2, zeros above
        last = _mm_or_si128(last, _mm_slli_si128(last, 3));
        last = _mm_or_si128(last, _mm_slli_si128(last, 6));
      } else {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row + i), x);
        last = kBpp == 4 ? _mm_shuffle_epi32(x, 0xff)
                         : _mm_shuffle_epi32(_mm_shufflehi_epi16(x, 0xff), 0xff);
      }
    }
    return i;
  }
#endif
  (void)row;
  (void)n;
  return 0;
}

// Reverses the filter of one scanline in place (PNG spec 1.2 section 6.2-6.6). `prev` is the
// previous unfiltered line (all zeros for the first line), kBpp the bytes per complete pixel.
// The left neighbour `a` is kept in registers: reading it back from `row` would put a
// store-to-load forwarding delay on every byte of the Sub, Average and Paeth chains.
template <int kBpp>
bool Unfilter(uint8_t type, uint8_t* row, const uint8_t* prev, size_t n) {
  uint8_t a[kBpp] = {}, c[kBpp] = {};
  switch (type) {
    case 0:  // None
      return true;
    case 1: {  // Sub: Raw(x) = Sub(x) + Raw(x - bpp)
      size_t i = SubVector<kBpp>(row, n);
      if (i > 0) std::memcpy(a, row + i - kBpp, kBpp);
      for (; i < n; i += kBpp)
        for (int k = 0; k < kBpp; ++k) row[i + k] = a[k] = static_cast<uint8_t>(row[i + k] + a[k]);
      return true;
    }
    case 2:  // Up: Raw(x) = Up(x) + Prior(x)
      for (size_t i = 0; i < n; ++i) row[i] = static_cast<uint8_t>(row[i] + prev[i]);
      return true;
    case 3:  // Average: Raw(x) = Average(x) + floor((Raw(x - bpp) + Prior(x)) / 2)
      for (size_t i = 0; i < n; i += kBpp)
        for (int k = 0; k < kBpp; ++k)
          row[i + k] = a[k] = static_cast<uint8_t>(row[i + k] + ((a[k] + prev[i + k]) >> 1));
      return true;
    case 4:  // Paeth: predictor of a = left, b = above, c = upper left (section 6.6)
      for (size_t i = 0; i < n; i += kBpp)
        for (int k = 0; k < kBpp; ++k) {
          const int b = prev[i + k];
          const int pa = std::abs(b - c[k]), pb = std::abs(a[k] - c[k]),
                    pc = std::abs(a[k] + b - 2 * c[k]);
          const int pred = (pa <= pb && pa <= pc) ? a[k] : (pb <= pc ? b : c[k]);
          row[i + k] = a[k] = static_cast<uint8_t>(row[i + k] + pred);
          c[k] = static_cast<uint8_t>(b);
        }
      return true;
    default:
      return false;
  }
}

bool Unfilter(uint8_t type, uint8_t* row, const uint8_t* prev, size_t n, size_t bpp) {
  switch (bpp) {
    case 1:
      return Unfilter<1>(type, row, prev, n);
    case 2:
      return Unfilter<2>(type, row, prev, n);
    case 3:
      return Unfilter<3>(type, row, prev, n);
    default:
      return Unfilter<4>(type, row, prev, n);
  }
}

// Copies one unfiltered line into an image row in OpenCV's order: BGR(A), native-endian 16 bit.
// The two common cases (16-bit grey: depth; 8-bit RGB: colour) reorder bytes 16 at a time by a
// shuffle; the rest, and the last bytes of a row, one sample at a time.
RGBDVO_SIMD_CLONES void StoreRow(const uint8_t* src, uint8_t* dst, int width, int channels_in,
                                 int bit_depth, int channels_out) {
  using v16u8 = uint8_t __attribute__((vector_size(16)));
  const auto load = [](const uint8_t* p) {
    v16u8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  if (bit_depth == 16) {
    // Big-endian samples (section 7.1): the two bytes of each swapped.
    const size_t n = size_t{2} * static_cast<size_t>(width);
    size_t i = 0;
    for (; i + 16 <= n; i += 16) {
      const v16u8 v = load(src + i);
      const v16u8 swapped =
          __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14);
      std::memcpy(dst + i, &swapped, sizeof swapped);
    }
    auto* d = reinterpret_cast<uint16_t*>(dst);
    for (size_t x = i / 2; x < n / 2; ++x)
      d[x] = static_cast<uint16_t>(src[2 * x] << 8 | src[2 * x + 1]);
  } else if (channels_in == 1) {
    std::memcpy(dst, src, static_cast<size_t>(width));
  } else {
    int x = 0;
    if (channels_in == 3 && channels_out == 3) {
      // 4 pixels (12 bytes) a step, loading and storing 16: the 4 bytes past them are written
      // again by the next step, so the last 2 pixels of the row are left to the loop below.
      for (; x + 6 <= width; x += 4, src += 12, dst += 12) {
        const v16u8 v = load(src);
        const v16u8 bgr =
            __builtin_shufflevector(v, v, 2, 1, 0, 5, 4, 3, 8, 7, 6, 11, 10, 9, 12, 13, 14, 15);
        std::memcpy(dst, &bgr, sizeof bgr);
      }
    }
    for (; x < width; ++x, src += channels_in, dst += channels_out) {
      dst[0] = src[2];
      dst[1] = src[1];
      dst[2] = src[0];
      if (channels_out == 4) dst[3] = src[3];
    }
  }
}

}  // namespace

PngDecodeResult DecodePng(const uint8_t* bytes, size_t size, int imread_flags) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size < 8 || std::memcmp(bytes, kSignature, 8) != 0) return Fail("not a PNG signature");
  if (imread_flags != cv::IMREAD_COLOR && imread_flags != cv::IMREAD_UNCHANGED)
    return Fail("imread flags other than IMREAD_COLOR / IMREAD_UNCHANGED");

  // Chunks: length, type, data, CRC-32 over type and data (section 5.3).
  const uint8_t* ihdr = nullptr;
  std::vector<const uint8_t*> idat_data;
  std::vector<size_t> idat_size;
  size_t idat_total = 0;
  bool idat_ended = false, iend = false;
  const auto truncated = [] {
    PngDecodeResult r = Fail("truncated chunk");
    r.truncated = true;
    return r;
  };
  for (size_t pos = 8; !iend;) {
    if (size - pos < 12) return truncated();
    const uint32_t len = BigEndian32(&bytes[pos]);
    if (len > 0x7fffffffu) return Fail("chunk length out of range");
    if (size - pos - 12 < len) return truncated();
    const uint8_t* type = &bytes[pos + 4];
    const uint8_t* data = type + 4;
    if (crc32_gzip_refl(0, type, len + 4) != BigEndian32(data + len))
      return Fail("chunk CRC mismatch");
    const std::string name(reinterpret_cast<const char*>(type), 4);
    for (const char ch : name)
      if (!std::isalpha(static_cast<unsigned char>(ch))) return Fail("invalid chunk name");
    if (pos == 8 && (name != "IHDR" || len != 13)) return Fail("IHDR is not first");
    if (name == "IHDR") {
      if (ihdr) return Fail("two IHDR chunks");
      ihdr = data;
    } else if (name == "IDAT") {
      if (idat_ended) return Fail("IDAT chunks not consecutive");
      idat_data.push_back(data);
      idat_size.push_back(len);
      idat_total += len;
    } else if (name == "IEND") {
      iend = true;
    } else if (name == "tRNS" || name == "eXIf" || name == "PLTE" || (type[0] & 0x20) == 0) {
      // Transparency and palettes change the channels, Exif may rotate the image; other
      // critical chunks are unknown. libpng ignores the remaining ancillary chunks for pixels.
      return Fail("chunk that changes decoding");
    }
    if (!idat_data.empty() && name != "IDAT") idat_ended = true;
    pos += 12 + size_t{len};
  }
  if (idat_data.empty()) return Fail("no IDAT chunk");

  // IHDR (section 11.2.2).
  const uint32_t width = BigEndian32(ihdr), height = BigEndian32(ihdr + 4);
  const int bit_depth = ihdr[8], colour_type = ihdr[9];
  if (ihdr[10] != 0 || ihdr[11] != 0) return Fail("unknown compression or filter method");
  if (ihdr[12] != 0) return Fail("interlaced");
  if (width == 0 || height == 0) return Fail("image size is zero");
  if (width > kMaxImageSide || height > kMaxImageSide) {
    PngDecodeResult r;
    r.reason = "PNG header claims " + std::to_string(width) + "x" + std::to_string(height) +
               " pixels, more than the " + std::to_string(kMaxImageSide) + " a side read here";
    r.too_large = true;
    return r;
  }
  int channels_in = 0, channels_out = 0;
  if (bit_depth == 8 && colour_type == 2) {
    channels_in = channels_out = 3;
  } else if (bit_depth == 8 && colour_type == 6) {
    channels_in = 4;
    channels_out = imread_flags == cv::IMREAD_COLOR ? 3 : 4;
  } else if ((bit_depth == 8 || bit_depth == 16) && colour_type == 0 &&
             imread_flags == cv::IMREAD_UNCHANGED) {
    channels_in = channels_out = 1;
  } else {
    return Fail("bit depth / colour type not handled");
  }

  // Inflate the concatenated IDAT data: a zlib stream (RFC 1950) whose Adler-32 ISA-L checks,
  // which must fill exactly height lines of one filter byte plus the samples.
  const size_t bpp = static_cast<size_t>(channels_in) * (bit_depth / 8);
  const size_t line = size_t{width} * bpp;
  // Deflate expands at most 1032:1 (RFC 1951: a 258-byte match per 2 bits at best), so data this
  // short cannot fill the image: refused before anything of the claimed size is allocated.
  constexpr size_t kMaxInflateRatio = 1032;
  if (size_t{height} * (line + 1) > kMaxInflateRatio * idat_total + kMaxInflateRatio)
    return Fail("IDAT data too short for the image size");
  // Scratch buffers kept per thread: fresh ones would cost a page fault every 4 KiB.
  thread_local std::vector<uint8_t> joined, raw;
  const uint8_t* zdata = idat_data[0];
  if (idat_data.size() > 1) {
    if (joined.size() < idat_total) joined.resize(idat_total);
    for (size_t i = 0, at = 0; i < idat_data.size(); at += idat_size[i], ++i)
      std::memcpy(&joined[at], idat_data[i], idat_size[i]);
    zdata = joined.data();
  }
  // Grown, never shrunk: colour and depth images alternate, and growing again would zero the
  // difference every time.
  const size_t expected = size_t{height} * (line + 1);
  if (raw.size() < expected + 16) raw.resize(expected + 16);  // padding for SubVector's last load
  if (idat_total > UINT32_MAX || expected > UINT32_MAX) return Fail("IDAT data above 4 GiB");
  thread_local inflate_state inflater;  // 85 KiB: not on the stack
  isal_inflate_init(&inflater);
  inflater.crc_flag = ISAL_ZLIB;                   // zlib header and Adler-32 checked
  inflater.next_in = const_cast<uint8_t*>(zdata);  // only read
  inflater.avail_in = static_cast<uint32_t>(idat_total);
  inflater.next_out = raw.data();
  inflater.avail_out = static_cast<uint32_t>(expected);
  // ISAL_DECOMP_OK: the stream ended within the output; it must also have filled it exactly.
  if (isal_inflate_stateless(&inflater) != ISAL_DECOMP_OK || inflater.total_out != expected)
    return Fail("zlib stream corrupt or of the wrong size");
  if (inflater.avail_in != 0) return Fail("data after the end of the zlib stream");

  PngDecodeResult r;
  r.image.create(static_cast<int>(height), static_cast<int>(width),
                 CV_MAKETYPE(bit_depth == 16 ? CV_16U : CV_8U, channels_out));
  thread_local std::vector<uint8_t> zeros;
  zeros.assign(line, 0);
  const uint8_t* prev = zeros.data();
  for (uint32_t y = 0; y < height; ++y) {
    uint8_t* row = &raw[y * (line + 1)];
    if (!Unfilter(row[0], row + 1, prev, line, bpp)) return Fail("unknown filter type");
    StoreRow(row + 1, r.image.ptr(static_cast<int>(y)), static_cast<int>(width), channels_in,
             bit_depth, channels_out);
    prev = row + 1;
  }
  r.success = true;
  return r;
}

std::optional<std::pair<uint32_t, uint32_t>> JpegSize(const uint8_t* bytes, size_t size) {
  if (size < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return std::nullopt;
  size_t pos = 2;
  while (pos + 4 <= size) {
    if (bytes[pos] != 0xFF) return std::nullopt;  // not at a marker: not ours to judge
    const uint8_t marker = bytes[pos + 1];
    if (marker == 0xFF) {  // fill byte
      ++pos;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // no length
      pos += 2;
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) return std::nullopt;  // end, or scan data before a frame
    const size_t length = size_t{bytes[pos + 2]} << 8 | bytes[pos + 3];
    const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
                       marker != 0xCC;  // SOF0-SOF15 but DHT, JPG, DAC
    if (frame && length >= 7 && pos + 9 <= size) {
      const uint32_t height = uint32_t{bytes[pos + 5]} << 8 | bytes[pos + 6];
      const uint32_t width = uint32_t{bytes[pos + 7]} << 8 | bytes[pos + 8];
      return std::make_pair(width, height);
    }
    pos += 2 + length;
  }
  return std::nullopt;
}

PngDecodeResult DecodePng(const std::vector<uint8_t>& bytes, int imread_flags) {
  return DecodePng(bytes.data(), bytes.size(), imread_flags);
}

std::optional<std::pair<uint32_t, uint32_t>> JpegSize(const std::vector<uint8_t>& bytes) {
  return JpegSize(bytes.data(), bytes.size());
}

cv::Mat ReadImage(const std::string& path, int imread_flags) {
  // The file's bytes, in a buffer kept per thread that grows and never shrinks: a fresh vector
  // (or one resized from a smaller image) would zero every byte before reading it.
  thread_local std::vector<uint8_t> buffer;
  // Checked first: fopen() opens a folder, whose size then reads as absurdly large.
  if (!InputFileSize(path, "image file")) return cv::Mat();
  size_t size = 0;
  if (FILE* f = std::fopen(path.c_str(), "rb")) {
    if (std::fseek(f, 0, SEEK_END) == 0) {
      const long length = std::ftell(f);
      if (length > kMaxImageFileBytes) {
        std::fclose(f);
        throw std::runtime_error(path + ": " + std::to_string(length) + " bytes, more than the " +
                                 std::to_string(kMaxImageFileBytes) + " an image file of at most " +
                                 std::to_string(kMaxImageSide) + " pixels a side can need");
      }
      if (length > 0 && std::fseek(f, 0, SEEK_SET) == 0) {
        size = static_cast<size_t>(length);
        if (buffer.size() < size) buffer.resize(size);
        if (std::fread(buffer.data(), 1, size, f) != size) size = 0;
      }
    }
    std::fclose(f);
  } else {
    return cv::Mat();  // missing or unreadable: nothing for cv::imread to add but a log line
  }
  const uint8_t* bytes = buffer.data();
  PngDecodeResult r = DecodePng(bytes, size, imread_flags);
  if (r.too_large) throw std::runtime_error(path + ": " + r.reason);
  if (r.truncated) return cv::Mat();
  if (const auto jpeg = JpegSize(bytes, size);
      jpeg && (jpeg->first > kMaxImageSide || jpeg->second > kMaxImageSide))
    throw std::runtime_error(path + ": JPEG header claims " + std::to_string(jpeg->first) + "x" +
                             std::to_string(jpeg->second) + " pixels, more than the " +
                             std::to_string(kMaxImageSide) + " a side read here");
  return r.success ? r.image : ImreadWithOpenCv(path, imread_flags);
}

}  // namespace rgbdvo
