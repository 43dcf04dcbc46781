#include "output_paths.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <optional>
#include <stdexcept>

namespace rgbdvo::cli {
namespace {

// The device and inode of an existing file: what makes two paths one file.
std::optional<std::pair<dev_t, ino_t>> FileId(const std::string& path) {
  struct stat st = {};
  if (stat(path.c_str(), &st) != 0) return std::nullopt;
  return std::make_pair(st.st_dev, st.st_ino);
}

bool Given(const OutputPath& o) { return !o.path.empty() && o.path != "-"; }

}  // namespace

void RefuseOutputsOntoInputs(const std::vector<OutputPath>& outputs,
                             const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::vector<std::pair<const OutputPath*, std::pair<dev_t, ino_t>>> existing;
  for (const OutputPath& o : outputs)
    if (Given(o))
      if (const auto id = FileId(o.path)) existing.emplace_back(&o, *id);
  // Only an output that exists can be an input; a new one costs no look at the inputs.
  if (!existing.empty())
    for (const std::string& in : inputs)
      if (const auto id = FileId(in))
        for (const auto& [o, out_id] : existing)
          if (*id == out_id)
            throw std::runtime_error(o->path + ": is an input of this command (" + in + "); give " +
                                     o->flag + " another file");
  for (size_t i = 0; i < outputs.size(); ++i)
    for (size_t j = i + 1; j < outputs.size(); ++j) {
      if (!Given(outputs[i]) || !Given(outputs[j])) continue;
      const auto a = FileId(outputs[i].path), b = FileId(outputs[j].path);
      std::error_code ec;
      const bool same = a && b ? *a == *b
                               : fs::weakly_canonical(outputs[i].path, ec) ==
                                     fs::weakly_canonical(outputs[j].path, ec);
      if (same)
        throw std::runtime_error(outputs[i].path + ": given for both " + outputs[i].flag + " and " +
                                 outputs[j].flag);
    }
}

}  // namespace rgbdvo::cli
