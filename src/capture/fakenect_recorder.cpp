#include "rgbdvo/capture/fakenect_recorder.hpp"

#include <filesystem>
#include <stdexcept>

#include "rgbdvo/sources/fakenect_files.hpp"

namespace fs = std::filesystem;

namespace rgbdvo {

FakenectRecorder::FakenectRecorder(const std::string& folder)
    : folder_(folder), index_(nullptr, &std::fclose) {
  std::error_code ec;
  if (fs::exists(folder, ec) && !(fs::is_directory(folder, ec) && fs::is_empty(folder, ec)))
    throw std::runtime_error(folder +
                             ": exists and is not an empty folder; refusing to "
                             "overwrite a recording (choose a new folder)");
  fs::create_directories(folder, ec);
  if (ec) throw std::runtime_error(folder + ": cannot create folder (" + ec.message() + ")");
  const std::string index = Path("INDEX.txt");
  index_.reset(std::fopen(index.c_str(), "wx"));
  if (!index_) throw std::runtime_error(index + ": cannot create");
}

std::string FakenectRecorder::Path(const std::string& name) const {
  return (fs::path(folder_) / name).string();
}

void FakenectRecorder::Index(const std::string& name) {
  if (std::fprintf(index_.get(), "%s\n", name.c_str()) < 0 || std::fflush(index_.get()) != 0)
    throw std::runtime_error(Path("INDEX.txt") + ": write failed (disk full?)");
  ++entries_;
}

void FakenectRecorder::AddColor(int64_t wallclock_us, uint32_t device_ts, const uint8_t* rgb,
                                int width, int height) {
  const std::string name = MakeFakenectName('r', wallclock_us, device_ts).ToString();
  WriteFakenectColor(Path(name), rgb, width, height);
  Index(name);
}

void FakenectRecorder::AddDepth(int64_t wallclock_us, uint32_t device_ts, const uint16_t* raw,
                                int width, int height) {
  const std::string name = MakeFakenectName('d', wallclock_us, device_ts).ToString();
  WriteFakenectDepth(Path(name), raw, width, height);
  Index(name);
}

void FakenectRecorder::AddAccel(int64_t wallclock_us, uint32_t device_ts, const void* state,
                                size_t bytes) {
  const std::string name = MakeFakenectName('a', wallclock_us, device_ts).ToString();
  WriteFakenectDump(Path(name), state, bytes);
  Index(name);
}

}  // namespace rgbdvo
