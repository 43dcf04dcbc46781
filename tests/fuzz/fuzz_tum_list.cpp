// Fuzz target: TUM rgb.txt / depth.txt lists.
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/sources/tum_source.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    rgbdvo::ReadTumList(rgbdvo::fuzz::InputFile(data, size, ".txt"));
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
