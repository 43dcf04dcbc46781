// CDR of the sensor_msgs messages: hand-built bytes in both byte orders, round trips, and every
// truncation and oversized length refused with the type and the field named.
#include "rgbdvo/io/ros2_messages.hpp"

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cstring>
#include <functional>
#include <stdexcept>

using namespace rgbdvo;

namespace {

// A mono8 image of 3x2 pixels stamped 1 s 2 ns, frame "f", laid out by hand: encapsulation,
// stamp, frame_id (u32 length with the NUL), two bytes of padding before height (4-aligned),
// encoding, is_bigendian, one byte of padding before step, data.
std::vector<uint8_t> HandBuiltImage(bool big_endian) {
  const auto u32 = [big_endian](uint32_t v) {
    std::vector<uint8_t> b(4);
    for (int i = 0; i < 4; ++i) b[big_endian ? 3 - i : i] = static_cast<uint8_t>(v >> (8 * i));
    return b;
  };
  std::vector<uint8_t> m = {0, static_cast<uint8_t>(big_endian ? 0 : 1), 0, 0};
  const auto add = [&m](const std::vector<uint8_t>& b) { m.insert(m.end(), b.begin(), b.end()); };
  add(u32(1));
  add(u32(2));
  add(u32(2));
  add({'f', 0, 0, 0});  // "f", NUL, padding
  add(u32(2));
  add(u32(3));
  add(u32(6));
  add({'m', 'o', 'n', 'o', '8', 0});
  add({0, 0});  // is_bigendian, padding
  add(u32(3));
  add(u32(6));
  add({10, 11, 12, 13, 14, 15});
  return m;
}

std::string RefusalOf(const std::function<void()>& decode) {
  try {
    decode();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

Ros2CameraInfo SomeCameraInfo() {
  Ros2CameraInfo c;
  c.header.sec = 1305031102;
  c.header.nanosec = 175304000;
  c.header.frame_id = "camera_rgb_optical_frame";
  c.height = 480, c.width = 640;
  c.distortion_model = "plumb_bob";
  c.d = {0.1, -0.2, 0.001, 0.002, 0.05};
  c.k = {520, 0, 320, 0, 521, 240, 0, 0, 1};
  c.r = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  c.p = {520, 0, 320, 0, 0, 521, 240, 0, 0, 0, 1, 0};
  c.binning_x = 1, c.roi_width = 7, c.roi_do_rectify = true;
  return c;
}

}  // namespace

TEST_CASE("CDR Image read from hand-built bytes in both byte orders") {
  for (const bool big : {false, true}) {
    const std::vector<uint8_t> bytes = HandBuiltImage(big);
    const Ros2Image m = DecodeRos2Image(bytes.data(), bytes.size());
    CHECK(m.header.sec == 1);
    CHECK(m.header.nanosec == 2);
    CHECK(m.header.frame_id == "f");
    CHECK(m.height == 2);
    CHECK(m.width == 3);
    CHECK(m.encoding == "mono8");
    CHECK(m.step == 3);
    CHECK(m.data == std::vector<uint8_t>{10, 11, 12, 13, 14, 15});
    CHECK(EncodeRos2Image(m, big) == bytes);
    CHECK(DecodeRos2Header(bytes.data(), bytes.size(), kRos2ImageType).Seconds() ==
          Approx(1.000000002));
  }
}

TEST_CASE("CDR CameraInfo, CompressedImage and Imu round trips in both byte orders") {
  for (const bool big : {false, true}) {
    const Ros2CameraInfo c = SomeCameraInfo();
    const std::vector<uint8_t> cb = EncodeRos2CameraInfo(c, big);
    const Ros2CameraInfo c2 = DecodeRos2CameraInfo(cb.data(), cb.size());
    CHECK(c2.header.frame_id == c.header.frame_id);
    CHECK(c2.distortion_model == "plumb_bob");
    CHECK(c2.d == c.d);
    CHECK(c2.k == c.k);
    CHECK(c2.p == c.p);
    CHECK(c2.roi_width == 7);
    CHECK(c2.roi_do_rectify);
    CHECK(EncodeRos2CameraInfo(c2, big) == cb);
    // The doubles of d start 8-aligned after the encapsulation header: after d's count, 4 bytes
    // of padding.
    const size_t d_at = 4 + 4 + 4 + 4 + 25 + 3 + 4 + 4 + 4 + 10 + 2 + 4 + 4;
    double d0 = 0;
    std::array<uint8_t, 8> raw{};
    std::copy(cb.begin() + static_cast<long>(d_at), cb.begin() + static_cast<long>(d_at) + 8,
              raw.begin());
    if (big) std::reverse(raw.begin(), raw.end());
    std::memcpy(&d0, raw.data(), 8);
    CHECK(d0 == 0.1);

    Ros2CompressedImage p;
    p.header.sec = 5;
    p.format = "16UC1; compressedDepth png";
    p.data = {1, 2, 3};
    const std::vector<uint8_t> pb = EncodeRos2CompressedImage(p, big);
    const Ros2CompressedImage p2 = DecodeRos2CompressedImage(pb.data(), pb.size());
    CHECK(p2.format == p.format);
    CHECK(p2.data == p.data);

    Ros2Imu imu;
    imu.header.nanosec = 9;
    imu.linear_acceleration = {0.1, -9.8, 0.2};
    imu.orientation = {0, 0, 0, 1};
    const std::vector<uint8_t> ib = EncodeRos2Imu(imu, big);
    const Ros2Imu imu2 = DecodeRos2Imu(ib.data(), ib.size());
    CHECK(imu2.linear_acceleration == imu.linear_acceleration);
    CHECK(imu2.orientation == imu.orientation);
    CHECK(imu2.header.nanosec == 9);
  }
}

TEST_CASE("CDR decoders refuse every truncation, naming the type and the field") {
  const std::vector<uint8_t> image = HandBuiltImage(false);
  for (size_t n = 0; n < image.size(); ++n) {
    const std::string why = RefusalOf([&] { DecodeRos2Image(image.data(), n); });
    INFO(n);
    CHECK_THAT(why, Catch::StartsWith("sensor_msgs/msg/Image: "));
  }
  const std::vector<uint8_t> info = EncodeRos2CameraInfo(SomeCameraInfo());
  for (size_t n = 0; n < info.size(); ++n) {
    INFO(n);
    CHECK_THAT(RefusalOf([&] { DecodeRos2CameraInfo(info.data(), n); }),
               Catch::StartsWith("sensor_msgs/msg/CameraInfo: "));
  }
  const std::vector<uint8_t> imu = EncodeRos2Imu(Ros2Imu());
  for (size_t n = 0; n < imu.size(); ++n)
    CHECK_THAT(RefusalOf([&] { DecodeRos2Imu(imu.data(), n); }),
               Catch::StartsWith("sensor_msgs/msg/Imu: "));
}

TEST_CASE("CDR decoders refuse lengths beyond the message and other encapsulations") {
  std::vector<uint8_t> image = HandBuiltImage(false);
  // The data's count (the last u32 before the six bytes) claims 4 GiB.
  for (size_t i = image.size() - 10; i < image.size() - 6; ++i) image[i] = 0xff;
  CHECK_THAT(RefusalOf([&] { DecodeRos2Image(image.data(), image.size()); }),
             Catch::Contains("data: 4294967295 bytes needed, 6 left"));

  Ros2CameraInfo c = SomeCameraInfo();
  c.d.clear();
  std::vector<uint8_t> info = EncodeRos2CameraInfo(c);
  const size_t count_at = 4 + 4 + 4 + 4 + 25 + 3 + 4 + 4 + 4 + 10 + 2;
  for (size_t i = count_at; i < count_at + 4; ++i) info[i] = 0xff;
  CHECK_THAT(RefusalOf([&] { DecodeRos2CameraInfo(info.data(), info.size()); }),
             Catch::Contains("d: 4294967295 doubles declared"));

  std::vector<uint8_t> xcdr2 = HandBuiltImage(false);
  xcdr2[1] = 0x07;
  CHECK_THAT(RefusalOf([&] { DecodeRos2Image(xcdr2.data(), xcdr2.size()); }),
             Catch::Contains("encapsulation header: 0x00 0x07"));
}
