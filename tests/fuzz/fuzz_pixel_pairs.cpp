// Fuzz target: the pairs CSV of rgbdvo calibrate.
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/calibrate/pixel_pairs_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    rgbdvo::LoadPixelPairs(rgbdvo::fuzz::InputFile(data, size, ".csv"));
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
