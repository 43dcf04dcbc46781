// Fuzz target: the calibration YAML loader.
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/sensor/calibration.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    rgbdvo::LoadCalibration(rgbdvo::fuzz::InputFile(data, size, ".yaml"));
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
