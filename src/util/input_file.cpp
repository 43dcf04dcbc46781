#include "rgbdvo/util/input_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace rgbdvo {
namespace {

// "64 MiB", "1 MiB", else bytes.
std::string Amount(std::uint64_t bytes) {
  if (bytes >= (1 << 20) && bytes % (1 << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

const char* Kind(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

}  // namespace

std::optional<std::uint64_t> InputFileSize(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  if (S_ISDIR(st.st_mode))
    throw std::runtime_error(path + ": is a directory (" + what + " expected)");
  if (!S_ISREG(st.st_mode))
    throw std::runtime_error(path + ": " + Kind(st.st_mode) + ", not a regular file (" + what +
                             " expected)");
  return static_cast<std::uint64_t>(st.st_size);
}

std::string ReadTextFile(const std::string& path, const std::string& what,
                         std::uint64_t max_bytes) {
  errno = 0;
  const std::optional<std::uint64_t> size = InputFileSize(path, what);
  if (!size) {
    // The error's text through the standard library (strerror_r), not strerror: thread-safe.
    const std::string why = errno ? std::generic_category().message(errno) : "not found";
    throw std::runtime_error(path + ": cannot open " + what + " (" + why + ")");
  }
  const auto too_large = [&](const std::string& bytes) {
    return std::runtime_error(path + ": " + bytes + ", above the limit of " + Amount(max_bytes) +
                              " for " + what + "s");
  };
  if (*size > max_bytes) throw too_large(std::to_string(*size) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open " + what);
  // Read to one byte past the limit: a file may grow after stat() or say 0 (/proc).
  std::string text;
  char chunk[1 << 16];
  while (in && text.size() <= max_bytes) {
    in.read(chunk, sizeof chunk);
    text.append(chunk, static_cast<size_t>(in.gcount()));
  }
  if (in.bad()) throw std::runtime_error(path + ": cannot read " + what);
  if (text.size() > max_bytes) throw too_large("more than " + std::to_string(max_bytes) + " bytes");
  return WithoutByteOrderMark(std::move(text));
}

std::string WithoutByteOrderMark(std::string s) {
  if (s.compare(0, 3, "\xEF\xBB\xBF") == 0) s.erase(0, 3);
  return s;
}

}  // namespace rgbdvo
