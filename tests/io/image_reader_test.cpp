#include "rgbdvo/io/image_reader.hpp"

#include <isa-l/crc.h>
#include <isa-l/igzip_lib.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "rgbdvo/io/png_decoder.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
namespace fs = std::filesystem;

namespace {

std::vector<uint8_t> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

bool Identical(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() &&
         (a.empty() || cv::norm(a, b, cv::NORM_INF) == 0);
}

// Random samples with smooth stretches, so that zlib finds matches and filters differ.
cv::Mat RandomImage(std::mt19937& rng, int rows, int cols, int type) {
  cv::Mat m(rows, cols, type);
  cv::randu(m, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
  cv::Mat smooth(rows, cols, type, cv::Scalar::all(static_cast<double>(rng() % 200)));
  if (rows > 1) smooth.rowRange(0, rows / 2).copyTo(m.rowRange(0, rows / 2));
  return m;
}

void PutBigEndian32(std::vector<uint8_t>& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(v >> s));
}

void PutChunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& data) {
  PutBigEndian32(out, static_cast<uint32_t>(data.size()));
  std::vector<uint8_t> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  out.insert(out.end(), body.begin(), body.end());
  PutBigEndian32(out, crc32_gzip_refl(0, body.data(), body.size()));
}

// `data` as a zlib stream (RFC 1950), compressed by ISA-L.
std::vector<uint8_t> Zlib(std::vector<uint8_t> data) {
  isal_zstream z;
  isal_deflate_stateless_init(&z);
  std::vector<uint8_t> out(data.size() + data.size() / 4 + 1024);
  z.gzip_flag = IGZIP_ZLIB;
  z.end_of_stream = 1;
  z.next_in = data.data();
  z.avail_in = static_cast<uint32_t>(data.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uint32_t>(out.size());
  REQUIRE(isal_deflate_stateless(&z) == COMP_OK);
  out.resize(z.total_out);
  return out;
}

// A PNG of IHDR, the zlib stream in two IDAT chunks (as libpng writes long streams) and IEND.
std::vector<uint8_t> PngOf(int width, int height, int bit_depth, int colour_type,
                           const std::vector<uint8_t>& zdata) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}, ihdr;
  PutBigEndian32(ihdr, width);
  PutBigEndian32(ihdr, height);
  ihdr.insert(ihdr.end(), {uint8_t(bit_depth), uint8_t(colour_type), 0, 0, 0});
  PutChunk(png, "IHDR", ihdr);
  const size_t half = zdata.size() / 2;
  PutChunk(png, "IDAT", std::vector<uint8_t>(zdata.begin(), zdata.begin() + half));
  PutChunk(png, "IDAT", std::vector<uint8_t>(zdata.begin() + half, zdata.end()));
  PutChunk(png, "IEND", {});
  return png;
}

// A PNG whose line y is filtered with type y % 5 (PNG spec 1.2 section 6), written by hand
// because cv::imwrite chooses the filters itself. `samples` holds the lines in file order.
std::vector<uint8_t> HandMadePng(const std::vector<uint8_t>& samples, int width, int height,
                                 int bit_depth, int colour_type, int bpp) {
  const size_t line = samples.size() / height;
  std::vector<uint8_t> filtered;
  for (int y = 0; y < height; ++y) {
    const uint8_t* cur = &samples[y * line];
    const uint8_t* up = y > 0 ? &samples[(y - 1) * line] : nullptr;
    const int type = y % 5;
    filtered.push_back(static_cast<uint8_t>(type));
    for (size_t i = 0; i < line; ++i) {
      const int a = i >= size_t(bpp) ? cur[i - bpp] : 0;
      const int b = up ? up[i] : 0;
      const int c = up && i >= size_t(bpp) ? up[i - bpp] : 0;
      const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
      const int paeth = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      const int pred[5] = {0, a, b, (a + b) / 2, paeth};
      filtered.push_back(static_cast<uint8_t>(cur[i] - pred[type]));
    }
  }
  return PngOf(width, height, bit_depth, colour_type, Zlib(filtered));
}

}  // namespace

TEST_CASE("DecodePng equals cv::imread on every image of the bundled TUM excerpt") {
  const std::string root = test::SourceDir() + "/data/tum_fr1_xyz_first30";
  int colour = 0, depth = 0;
  for (const auto& [folder, flags] :
       {std::pair{"rgb", cv::IMREAD_COLOR}, std::pair{"depth", cv::IMREAD_UNCHANGED}}) {
    for (const auto& e : fs::directory_iterator(root + "/" + folder)) {
      const std::string path = e.path().string();
      INFO(path);
      const PngDecodeResult r = DecodePng(ReadBytes(path), flags);
      REQUIRE(r.success);
      CHECK(Identical(r.image, cv::imread(path, flags)));
      ++(flags == cv::IMREAD_COLOR ? colour : depth);
    }
  }
  CHECK(colour >= 30);
  CHECK(depth >= 30);
}

TEST_CASE("DecodePng equals cv::imread on cv::imwrite PNGs of odd sizes, 8 and 16 bit") {
  std::mt19937 rng(7);
  const std::string dir = test::MakeTempDir("image_reader");
  const cv::Size sizes[] = {{1, 1}, {1, 9}, {9, 1}, {3, 5}, {17, 13}, {33, 7}, {641, 31}};
  for (const cv::Size size : sizes) {
    for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1}) {
      const std::string path = dir + "/img.png";
      REQUIRE(cv::imwrite(path, RandomImage(rng, size.height, size.width, type)));
      for (const int flags : {cv::IMREAD_COLOR, cv::IMREAD_UNCHANGED}) {
        INFO(size << " type " << type << " flags " << flags);
        const PngDecodeResult r = DecodePng(ReadBytes(path), flags);
        // Grey images to colour and 16 bit to 8 bit are left to cv::imread.
        const bool handled = type == CV_8UC3 || type == CV_8UC4 || flags == cv::IMREAD_UNCHANGED;
        CHECK(r.success == handled);
        if (r.success) CHECK(Identical(r.image, cv::imread(path, flags)));
        CHECK(Identical(ReadImage(path, flags), cv::imread(path, flags)));
      }
    }
  }
}

TEST_CASE("DecodePng undoes all five PNG filter types for 1-, 2-, 3- and 4-byte pixels") {
  std::mt19937 rng(11);
  const std::string dir = test::MakeTempDir("png_filters");
  struct Kind {
    int bit_depth, colour_type, bpp;
  };
  for (const Kind k : {Kind{8, 0, 1}, Kind{16, 0, 2}, Kind{8, 2, 3}, Kind{8, 6, 4}}) {
    for (const int width : {1, 2, 5, 6, 7, 16, 37, 100}) {
      const int height = 11;
      std::vector<uint8_t> samples(size_t(width) * height * k.bpp);
      for (size_t i = 0; i < samples.size(); ++i)
        samples[i] = static_cast<uint8_t>(i % 7 < 4 ? rng() : 100 + i % 13);
      const std::string path = dir + "/f.png";
      WriteBytes(path, HandMadePng(samples, width, height, k.bit_depth, k.colour_type, k.bpp));
      for (const int flags : {cv::IMREAD_COLOR, cv::IMREAD_UNCHANGED}) {
        if (k.colour_type == 0 && flags == cv::IMREAD_COLOR) continue;
        INFO("colour type " << k.colour_type << " depth " << k.bit_depth << " width " << width);
        const PngDecodeResult r = DecodePng(ReadBytes(path), flags);
        REQUIRE(r.success);
        const cv::Mat expected = cv::imread(path, flags);
        REQUIRE(!expected.empty());
        CHECK(Identical(r.image, expected));
      }
    }
  }
}

TEST_CASE("DecodePng leaves corrupt PNGs to cv::imread and refuses truncated ones itself") {
  std::mt19937 rng(3);
  const std::string dir = test::MakeTempDir("png_corrupt");
  const std::string path = dir + "/c.png";
  REQUIRE(cv::imwrite(path, RandomImage(rng, 40, 50, CV_8UC3)));
  const std::vector<uint8_t> good = ReadBytes(path);
  REQUIRE(DecodePng(good, cv::IMREAD_COLOR).success);

  for (const size_t keep : {size_t{0}, size_t{8}, size_t{40}, good.size() / 2, good.size() - 1}) {
    INFO("truncated to " << keep << " bytes");
    const std::vector<uint8_t> cut(good.begin(), good.begin() + keep);
    const PngDecodeResult r = DecodePng(cut, cv::IMREAD_COLOR);
    CHECK_FALSE(r.success);
    CHECK(r.truncated == (keep >= 8));  // a PNG signature, then the file ends inside a chunk
    WriteBytes(path, cut);
    // No image, as cv::imread gives none (it prints libpng's "Read Error" for a cut PNG too).
    CHECK(ReadImage(path, cv::IMREAD_COLOR).empty());
    CHECK(cv::imread(path, cv::IMREAD_COLOR).empty());
  }
  std::vector<uint8_t> flipped = good;
  flipped[good.size() / 2] ^= 0x10;  // inside IDAT: the chunk CRC no longer matches
  const PngDecodeResult r = DecodePng(flipped, cv::IMREAD_COLOR);
  CHECK_FALSE(r.success);
  CHECK_FALSE(r.truncated);
  CHECK(r.reason == "chunk CRC mismatch");
  CHECK_FALSE(DecodePng(good, cv::IMREAD_GRAYSCALE).success);
  CHECK(ReadImage(dir + "/missing.png", cv::IMREAD_COLOR).empty());
}

TEST_CASE("DecodePng rejects a zlib stream that does not fill the image exactly or is corrupt") {
  std::vector<uint8_t> samples(4 * 3 * 3, 50);
  std::vector<uint8_t> png = HandMadePng(samples, 4, 3, 8, 2, 3);
  CHECK(DecodePng(png, cv::IMREAD_COLOR).success);
  // IHDR claims 4 x 3 but the stream holds only 2 lines (IHDR's CRC recomputed).
  std::vector<uint8_t> short_png = HandMadePng(std::vector<uint8_t>(4 * 2 * 3, 50), 4, 2, 8, 2, 3);
  short_png[8 + 8 + 7] = 3;  // height byte of IHDR
  const uint32_t crc = crc32_gzip_refl(0, &short_png[12], 17);
  for (int i = 0; i < 4; ++i) short_png[29 + i] = static_cast<uint8_t>(crc >> (24 - 8 * i));
  const PngDecodeResult r = DecodePng(short_png, cv::IMREAD_COLOR);
  CHECK_FALSE(r.success);
  CHECK(r.reason == "zlib stream corrupt or of the wrong size");

  // 4 x 3 RGB, unfiltered: 3 lines of a filter byte and 12 samples.
  std::vector<uint8_t> lines;
  for (int y = 0; y < 3; ++y) {
    lines.push_back(0);
    for (int i = 0; i < 12; ++i) lines.push_back(static_cast<uint8_t>(20 * y + i));
  }
  REQUIRE(DecodePng(PngOf(4, 3, 8, 2, Zlib(lines)), cv::IMREAD_COLOR).success);
  // A stream holding a line more than the image.
  std::vector<uint8_t> more = lines;
  more.insert(more.end(), lines.begin(), lines.begin() + 13);
  CHECK(DecodePng(PngOf(4, 3, 8, 2, Zlib(more)), cv::IMREAD_COLOR).reason ==
        "zlib stream corrupt or of the wrong size");
  // A wrong Adler-32 at the stream's end (the chunks' CRCs are right).
  std::vector<uint8_t> wrong_sum = Zlib(lines);
  wrong_sum.back() ^= 1;
  CHECK(DecodePng(PngOf(4, 3, 8, 2, wrong_sum), cv::IMREAD_COLOR).reason ==
        "zlib stream corrupt or of the wrong size");
  // Bytes after the stream's end.
  std::vector<uint8_t> trailing = Zlib(lines);
  trailing.insert(trailing.end(), {1, 2, 3});
  CHECK(DecodePng(PngOf(4, 3, 8, 2, trailing), cv::IMREAD_COLOR).reason ==
        "data after the end of the zlib stream");
}

TEST_CASE("ReadImage refuses a PNG claiming more pixels than any sensor before allocating them") {
  const std::string dir = test::MakeTempDir("png_size");
  // A valid header of 30000x30000 RGB (2.7 GB of samples) over a few bytes of data.
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}, ihdr;
  PutBigEndian32(ihdr, 30000);
  PutBigEndian32(ihdr, 30000);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  PutChunk(png, "IHDR", ihdr);
  PutChunk(png, "IDAT", {0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01});
  PutChunk(png, "IEND", {});
  const std::string path = dir + "/huge.png";
  WriteBytes(path, png);
  const PngDecodeResult r = DecodePng(png, cv::IMREAD_COLOR);
  CHECK(r.too_large);
  CHECK_THROWS_WITH(ReadImage(path, cv::IMREAD_COLOR), Catch::Contains("huge.png") &&
                                                           Catch::Contains("30000x30000") &&
                                                           Catch::Contains("4096"));
  // Within the limit but with far too little data for the size (deflate expands at most 1032:1):
  // refused by the decoder, left to cv::imread, which finds it corrupt.
  std::vector<uint8_t> short_png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  ihdr.clear();
  PutBigEndian32(ihdr, 4000);
  PutBigEndian32(ihdr, 4000);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  PutChunk(short_png, "IHDR", ihdr);
  PutChunk(short_png, "IDAT", {0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01});
  PutChunk(short_png, "IEND", {});
  const PngDecodeResult s = DecodePng(short_png, cv::IMREAD_COLOR);
  CHECK_FALSE(s.success);
  CHECK_FALSE(s.too_large);
  CHECK_THAT(s.reason, Catch::Contains("too short"));
}

TEST_CASE("ReadImage refuses a JPEG claiming more pixels than any sensor, reads a normal one") {
  const std::string dir = test::MakeTempDir("jpeg_size");
  cv::Mat img(48, 64, CV_8UC3, cv::Scalar(40, 90, 160));
  std::vector<uint8_t> jpeg;
  REQUIRE(cv::imencode(".jpg", img, jpeg));
  REQUIRE(JpegSize(jpeg) == std::make_pair(uint32_t{64}, uint32_t{48}));
  WriteBytes(dir + "/ok.jpg", jpeg);
  CHECK(ReadImage(dir + "/ok.jpg", cv::IMREAD_COLOR).size() == cv::Size(64, 48));
  // The same file with its frame header claiming 40000 x 30000.
  for (size_t i = 2; i + 9 < jpeg.size(); ++i)
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {
      jpeg[i + 5] = 30000 >> 8;
      jpeg[i + 6] = 30000 & 0xFF;
      jpeg[i + 7] = 40000 >> 8;
      jpeg[i + 8] = 40000 & 0xFF;
      break;
    }
  REQUIRE(JpegSize(jpeg) == std::make_pair(uint32_t{40000}, uint32_t{30000}));
  WriteBytes(dir + "/huge.jpg", jpeg);
  CHECK_THROWS_WITH(ReadImage(dir + "/huge.jpg", cv::IMREAD_COLOR),
                    Catch::Contains("huge.jpg") && Catch::Contains("40000x30000"));
  CHECK_FALSE(JpegSize({0xFF, 0xD8, 0xFF}));  // truncated: no answer, no crash
}
