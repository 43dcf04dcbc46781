#pragma once
// Input files opened by path, checked the same way for every reader: what is at the path, and
// the text of list, trajectory, calibration and configuration files.

#include <cstdint>
#include <optional>
#include <string>

namespace rgbdvo {

// The size of the file at path, or nullopt when nothing can be found there (missing, no
// permission to look). Throws std::runtime_error "<path>: is a directory (<what> expected)".
std::optional<std::uint64_t> InputFileSize(const std::string& path, const std::string& what);

// The text of the file at path, without a UTF-8 byte order mark at its start (editors on Windows
// write one; it is invisible in a message quoting the first line). Throws std::runtime_error
// "<path>: cannot open <what> (<reason>)" and InputFileSize's errors.
std::string ReadTextFile(const std::string& path, const std::string& what);

// s without a UTF-8 byte order mark at its start.
std::string WithoutByteOrderMark(std::string s);

}  // namespace rgbdvo
