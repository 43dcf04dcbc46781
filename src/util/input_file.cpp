#include "rgbdvo/util/input_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

namespace rgbdvo {

std::optional<std::uint64_t> InputFileSize(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  if (S_ISDIR(st.st_mode))
    throw std::runtime_error(path + ": is a directory (" + what + " expected)");
  return static_cast<std::uint64_t>(st.st_size);
}

std::string ReadTextFile(const std::string& path, const std::string& what) {
  errno = 0;
  if (!InputFileSize(path, what)) {
    // The error's text through the standard library (strerror_r), not strerror: thread-safe.
    const std::string why = errno ? std::generic_category().message(errno) : "not found";
    throw std::runtime_error(path + ": cannot open " + what + " (" + why + ")");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open " + what);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(path + ": cannot read " + what);
  return WithoutByteOrderMark(std::move(text));
}

std::string WithoutByteOrderMark(std::string s) {
  if (s.compare(0, 3, "\xEF\xBB\xBF") == 0) s.erase(0, 3);
  return s;
}

}  // namespace rgbdvo
