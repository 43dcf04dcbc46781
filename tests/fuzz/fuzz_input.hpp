#pragma once
// What the fuzz targets share: the entry point libFuzzer calls, and the input written to a file
// for the parsers that read files. Each target feeds one parser; an exception derived from
// std::exception is the parser refusing the input (expected), anything else (a crash, a
// sanitizer report, another exception, a hang, an allocation beyond libFuzzer's limit) is a
// finding.

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace rgbdvo::fuzz {

// Writes the input to this process's scratch file (in $TMPDIR) and returns its path; the file
// is removed when the process exits normally.
const std::string& InputFile(const uint8_t* data, size_t size, const char* extension);

}  // namespace rgbdvo::fuzz
