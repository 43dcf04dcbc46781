#pragma once
// Outputs that would overwrite an input: refused before anything is opened or written.

#include <string>
#include <utility>
#include <vector>

namespace rgbdvo::cli {

// An output file and the flag that named it ("--tum").
struct OutputPath {
  std::string path;
  std::string flag;
};

// Throws naming the output and the input when an output (empty paths and "-" ignored) is the
// same file as one of `inputs` (by device and inode, so links and other spellings are caught),
// or when two outputs are the same file.
void RefuseOutputsOntoInputs(const std::vector<OutputPath>& outputs,
                             const std::vector<std::string>& inputs);

}  // namespace rgbdvo::cli
