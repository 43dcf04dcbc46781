// Fuzz target: fakenect INDEX.txt (and each listed name).
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/sources/fakenect_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    for (const std::string& name :
         rgbdvo::ReadFakenectIndex(rgbdvo::fuzz::InputFile(data, size, ".txt")))
      rgbdvo::ParseFakenectName(name);
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  return 0;
}
