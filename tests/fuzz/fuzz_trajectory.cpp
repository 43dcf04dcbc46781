// Fuzz target: the trajectory reader (TUM and CSV).
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/io/trajectory_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    rgbdvo::ReadTrajectory(rgbdvo::fuzz::InputFile(data, size, ".txt"));
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
