// Fuzz target: fakenect's colour PPM and depth PGM files.
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/sources/fakenect_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = rgbdvo::fuzz::InputFile(data, size, ".pnm");
  try {
    rgbdvo::ReadFakenectColor(path);
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  try {
    rgbdvo::ReadFakenectDepth(path);
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
