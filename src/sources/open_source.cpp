#include "rgbdvo/sources/open_source.hpp"

#include <filesystem>
#include <stdexcept>

namespace rgbdvo {

std::unique_ptr<FrameSource> OpenRecording(const std::string& folder,
                                           const SourceOptions& options) {
  if (!std::filesystem::is_directory(folder)) throw std::runtime_error(folder + ": no such folder");
  if (IsTumFolder(folder)) return std::make_unique<TumSource>(folder, options.tum);
  if (IsFakenectFolder(folder)) return std::make_unique<FakenectSource>(folder, options.fakenect);
  throw std::runtime_error(folder +
                           ": unknown recording layout (expected TUM RGB-D: rgb.txt and "
                           "depth.txt, or libfreenect fakenect: INDEX.txt)");
}

}  // namespace rgbdvo
