// Fuzz target: the CDR decoders of the four sensor_msgs types, each on the whole input, and the
// header alone. Every refusal is a std::runtime_error; a decoded message re-encodes to bytes
// that decode and re-encode to the same bytes (compared as bytes: a NaN is not equal to itself).
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/io/ros2_messages.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rgbdvo;
  try {
    const bool big_endian = size > 1 && data[1] == 0;
    const std::vector<uint8_t> again = EncodeRos2Image(DecodeRos2Image(data, size), big_endian);
    if (EncodeRos2Image(DecodeRos2Image(again.data(), again.size()), big_endian) != again)
      __builtin_trap();
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  try {
    DecodeRos2CompressedImage(data, size);
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  try {
    const std::vector<uint8_t> again = EncodeRos2CameraInfo(DecodeRos2CameraInfo(data, size));
    if (EncodeRos2CameraInfo(DecodeRos2CameraInfo(again.data(), again.size())) != again)
      __builtin_trap();
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  try {
    DecodeRos2Imu(data, size);
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  try {
    DecodeRos2Header(data, size, kRos2ImageType);
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
