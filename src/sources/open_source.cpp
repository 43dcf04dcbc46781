#include "rgbdvo/sources/open_source.hpp"

#include <filesystem>
#include <stdexcept>

#include "rgbdvo/sources/association_file.hpp"

namespace rgbdvo {

std::unique_ptr<FrameSource> OpenRecording(const std::string& folder,
                                           const SourceOptions& options) {
  namespace fs = std::filesystem;
  const auto from_associations = [&](const std::string& file) {
    return std::make_unique<TumSource>(fs::path(file).parent_path().string(),
                                       ReadAssociations(file), file, options.tum);
  };
  if (IsAssociationFile(folder)) return from_associations(folder);
  if (!fs::is_directory(folder))
    throw std::runtime_error(folder + (fs::exists(folder) ? ": neither a recording folder nor an "
                                                            "association file (t_rgb rgb_path "
                                                            "t_depth depth_path a line)"
                                                          : ": no such folder"));
  if (IsTumFolder(folder)) return std::make_unique<TumSource>(folder, options.tum);
  const std::string associations = (fs::path(folder) / "associations.txt").string();
  if (fs::is_regular_file(associations)) return from_associations(associations);
  if (IsFakenectFolder(folder)) return std::make_unique<FakenectSource>(folder, options.fakenect);
  throw std::runtime_error(folder +
                           ": unknown recording layout (expected TUM RGB-D: rgb.txt and "
                           "depth.txt, or associations.txt, or libfreenect fakenect: INDEX.txt)");
}

}  // namespace rgbdvo
