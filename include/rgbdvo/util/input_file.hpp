#pragma once
// Input files opened by path, checked the same way for every reader: what is at the path (open()
// on a FIFO waits for a writer forever, a folder reads as a file of absurd size, /dev/zero never
// ends), and how much a text file may hold.

#include <cstdint>
#include <optional>
#include <string>

namespace rgbdvo {

// The size of the regular file at path, or nullopt when nothing can be found there (missing, no
// permission to look). Throws std::runtime_error for anything else, before it is opened:
// "<path>: is a directory (<what> expected)", "<path>: a FIFO, not a regular file (<what>
// expected)" (or a character device, block device, socket).
std::optional<std::uint64_t> InputFileSize(const std::string& path, const std::string& what);

// What a text file may hold: a configuration or calibration is a page; a list of frames or a
// trajectory of a long recording is far below these.
constexpr std::uint64_t kMaxConfigFileBytes = std::uint64_t{1} << 20;
constexpr std::uint64_t kMaxListFileBytes = std::uint64_t{64} << 20;
constexpr std::uint64_t kMaxTrajectoryFileBytes = std::uint64_t{256} << 20;

// The text of the regular file at path, without a UTF-8 byte order mark at its start (editors on
// Windows write one; it is invisible in a message quoting the first line). Throws
// std::runtime_error "<path>: cannot open <what> (<reason>)", InputFileSize's errors, and
// "<path>: <N> bytes, above the limit of <max_bytes> for <what>s" (also for a file that grows
// past it while read).
std::string ReadTextFile(const std::string& path, const std::string& what, std::uint64_t max_bytes);

// s without a UTF-8 byte order mark at its start.
std::string WithoutByteOrderMark(std::string s);

}  // namespace rgbdvo
