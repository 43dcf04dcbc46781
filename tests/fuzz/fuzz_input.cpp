#include "fuzz_input.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace rgbdvo::fuzz {

namespace {

// The scratch file, removed when the process exits normally (after a crash it stays, with the
// input that caused it).
struct ScratchFile {
  std::string path;
  ~ScratchFile() {
    if (!path.empty()) std::remove(path.c_str());
  }
};

}  // namespace

const std::string& InputFile(const uint8_t* data, size_t size, const char* extension) {
  static ScratchFile scratch;
  if (!scratch.path.empty()) std::remove(scratch.path.c_str());  // another extension before
  scratch.path = (std::filesystem::temp_directory_path() /
                  ("rgbdvo_fuzz_" + std::to_string(getpid()) + extension))
                     .string();
  FILE* f = std::fopen(scratch.path.c_str(), "wb");
  if (!f || std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return scratch.path;
}

}  // namespace rgbdvo::fuzz
