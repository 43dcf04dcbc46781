#include "rgbdvo/util/temp_dir.hpp"

#include <stdlib.h>  // mkdtemp (POSIX)

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace rgbdvo {

std::string MakeTempDir(const std::string& prefix) {
  std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "XXXXXX")).string();
  if (!mkdtemp(tmpl.data()))
    // The error's text through the standard library (strerror_r), not strerror: thread-safe.
    throw std::runtime_error(tmpl + ": cannot create a temporary folder (" +
                             std::generic_category().message(errno) + ")");
  return tmpl;
}

ScopedTempDir::~ScopedTempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace rgbdvo
