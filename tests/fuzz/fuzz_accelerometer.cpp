// Fuzz target: TUM accelerometer.txt.
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/sources/accelerometer_track.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const rgbdvo::AccelerometerTrack track(
        rgbdvo::ReadTumAccelerometer(rgbdvo::fuzz::InputFile(data, size, ".txt")));
    (void)track.GravityAt(1305031102.2);
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
