#include "fuzz_input.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace rgbdvo::fuzz {

const std::string& InputFile(const uint8_t* data, size_t size, const char* extension) {
  static std::string path;
  path = (std::filesystem::temp_directory_path() /
          ("rgbdvo_fuzz_" + std::to_string(getpid()) + extension))
             .string();
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

}  // namespace rgbdvo::fuzz
