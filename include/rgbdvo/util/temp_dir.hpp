#pragma once
// Fresh private folders under the system's temporary directory (mkdtemp: unique, mode 0700).

#include <string>

namespace rgbdvo {

// Creates <tmp>/<prefix>XXXXXX and returns its path; the caller owns (and removes) it. Throws
// std::runtime_error when it cannot be created.
std::string MakeTempDir(const std::string& prefix);

// A MakeTempDir folder removed with everything in it when this goes out of scope.
class ScopedTempDir {
 public:
  explicit ScopedTempDir(const std::string& prefix) : path_(MakeTempDir(prefix)) {}
  ~ScopedTempDir();
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace rgbdvo
