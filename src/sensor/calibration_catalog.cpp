#include "rgbdvo/sensor/calibration_catalog.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

namespace fs = std::filesystem;

std::string DescriptionOf(const std::string& path) {
  try {
    return LoadCalibration(path).description;
  } catch (const std::exception&) {
    return "";  // listed all the same; using it will say what is wrong
  }
}

void AddIfFolder(const fs::path& folder, std::vector<std::string>* out) {
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec)) return;
  const std::string s = fs::weakly_canonical(folder, ec).string();
  if (std::find(out->begin(), out->end(), s) == out->end()) out->push_back(s);
}

}  // namespace

std::vector<std::string> CalibrationSearchPath() {
  std::vector<std::string> folders;
  if (const char* env = std::getenv("RGBDVO_CALIB_PATH")) {
    std::istringstream list(env);
    for (std::string folder; std::getline(list, folder, ':');) AddIfFolder(folder, &folders);
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) AddIfFolder(exe.parent_path().parent_path() / "share" / "rgbdvo" / "calib", &folders);
#ifdef RGBDVO_INSTALL_CALIB_DIR
  AddIfFolder(RGBDVO_INSTALL_CALIB_DIR, &folders);
#endif
#ifdef RGBDVO_SOURCE_CALIB_DIR
  AddIfFolder(RGBDVO_SOURCE_CALIB_DIR, &folders);
#endif
  return folders;
}

std::string FindCalibration(const std::string& name_or_path) {
  std::error_code ec;
  if (fs::is_regular_file(name_or_path, ec)) return name_or_path;
  const std::vector<std::string> folders = CalibrationSearchPath();
  if (!name_or_path.empty() && name_or_path.find('/') == std::string::npos) {
    for (const std::string& folder : folders)
      for (const std::string& file : {name_or_path, name_or_path + ".yaml"}) {
        const fs::path candidate = fs::path(folder) / file;
        if (fs::is_regular_file(candidate, ec)) return candidate.string();
      }
  }
  // Something there, but not a file: say what it is (a folder, a FIFO) rather than "no such file".
  if (fs::exists(name_or_path, ec)) InputFileSize(name_or_path, "calibration file");
  std::string where;
  for (const std::string& folder : folders) where += (where.empty() ? "" : ", ") + folder;
  throw std::runtime_error("calibration '" + name_or_path +
                           "': no such file, and no calibration of that name in " +
                           (where.empty() ? std::string("any calibration folder") : where) +
                           " (`rgbdvo calibrations` lists them)");
}

std::vector<CalibrationEntry> ListCalibrations() {
  std::map<std::string, CalibrationEntry> by_name;
  for (const std::string& folder : CalibrationSearchPath()) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
      if (!e.is_regular_file(ec) || e.path().extension() != ".yaml") continue;
      const std::string name = e.path().stem().string();
      if (by_name.count(name)) continue;
      by_name[name] = {name, e.path().string(), DescriptionOf(e.path().string())};
    }
  }
  std::vector<CalibrationEntry> entries;
  entries.reserve(by_name.size());
  for (auto& [name, entry] : by_name) entries.push_back(std::move(entry));
  return entries;
}

}  // namespace rgbdvo
