#include "rgbdvo/sources/fakenect_source.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"
#include "rgbdvo/sources/fakenect_files.hpp"
#include "rgbdvo/sources/stream_pairer.hpp"
#include "rgbdvo/util/display_text.hpp"

namespace fs = std::filesystem;

namespace rgbdvo {

void FakenectSourceOptions::Check() const {
  if (!(max_time_diff_s > 0))
    throw std::invalid_argument("FakenectSourceOptions.max_time_diff_s must be > 0");
}

namespace {

bool IsFrameFile(const fs::directory_entry& e) {
  if (!e.is_regular_file()) return false;
  const std::optional<FakenectName> n = ParseFakenectName(e.path().filename().string());
  return n && (n->type == 'r' || n->type == 'd');
}

// Without INDEX.txt: every r-/d-/a- file of the folder in wall-clock order.
std::vector<std::string> ListFakenectFiles(const std::string& folder) {
  std::vector<std::pair<int64_t, std::string>> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    const std::optional<FakenectName> n = ParseFakenectName(name);
    if (e.is_regular_file() && n) files.emplace_back(n->wallclock_us, name);
  }
  std::sort(files.begin(), files.end());
  std::vector<std::string> names;
  names.reserve(files.size());
  for (auto& f : files) names.push_back(std::move(f.second));
  return names;
}

}  // namespace

bool IsFakenectFolder(const std::string& folder) {
  if (fs::is_regular_file(fs::path(folder) / "INDEX.txt")) return true;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    if (IsFrameFile(e)) return true;
  return false;
}

FakenectSource::FakenectSource(const std::string& folder, const FakenectSourceOptions& options)
    : folder_(folder), options_(options) {
  options_.Check();
  if (!fs::is_directory(folder)) throw std::runtime_error(folder + ": no such folder");
  const std::string index = (fs::path(folder) / "INDEX.txt").string();
  has_index_ = fs::is_regular_file(index);
  const std::vector<std::string> names =
      has_index_ ? ReadFakenectIndex(index) : ListFakenectFiles(folder);
  StreamPairer<Entry> pairer(std::llround(options_.max_time_diff_s * 1e6), options_.pairing);
  std::string first_missing;
  int missing = 0;
  auto add = [this](std::vector<StampedPair<Entry>> done) {
    for (auto& p : done) pairs_.emplace_back(std::move(p.color.value), std::move(p.depth.value));
  };
  std::vector<FakenectName> parsed;
  std::vector<Entry> accel;
  for (size_t i = 0; i < names.size(); ++i) {
    const std::optional<FakenectName> name = ParseFakenectName(names[i]);
    if (!name)
      throw std::runtime_error(index + ": entry " + std::to_string(i + 1) + " '" +
                               Excerpt(names[i]) + "' is not <r|d|a>-<seconds>-<timestamp>.<ext>");
    if (!fs::is_regular_file(fs::path(folder) / names[i]) && missing++ == 0)
      first_missing = names[i];
    parsed.push_back(*name);
  }
  // Pair by the device's clock; recordings without device timestamps (all equal) by the host's.
  by_device_clock_ = false;
  for (const FakenectName& n : parsed)
    if (n.device_ts != parsed.front().device_ts) by_device_clock_ = true;
  // With the device's clock the frames are also stamped by it (KinectClock::OnHost), as the
  // live capture stamps them.
  KinectClock clock;
  for (size_t i = 0; i < parsed.size(); ++i) {
    const FakenectName& name = parsed[i];
    const int64_t t = by_device_clock_ ? clock.Micros(name.device_ts) : name.wallclock_us;
    const double seconds = by_device_clock_
                               ? static_cast<double>(clock.OnHost(t, name.wallclock_us)) * 1e-6
                               : name.seconds();
    const Stamped<Entry> e{t, {names[i], seconds}};
    if (name.type == 'r') {
      ++color_frames_;
      add(pairer.AddColor(e));
    } else if (name.type == 'd') {
      ++depth_frames_;
      add(pairer.AddDepth(e));
    } else {
      ++accel_entries_;
      accel.push_back(e.value);
    }
  }
  add(pairer.Finish());
  unpaired_ = pairer.unpaired();
  if (missing > 0)
    throw std::runtime_error((fs::path(folder) / first_missing).string() +
                             ": listed in INDEX.txt but missing (" + std::to_string(missing) +
                             " missing files in all)");
  if (pairs_.empty())
    throw std::runtime_error(folder + ": empty sequence (" + std::to_string(color_frames_) +
                             " colour and " + std::to_string(depth_frames_) +
                             " depth frames in INDEX.txt, no pair within " +
                             std::to_string(options_.max_time_diff_s) + " s)");
  if (options_.accelerometer) {
    if (accel.empty())
      throw std::runtime_error(folder +
                               ": no accelerometer entries (a-*.dump; accelerometer "
                               "readings needed)");
    std::vector<AccelReading> readings;
    readings.reserve(accel.size());
    for (const Entry& a : accel)
      readings.push_back({a.seconds, ApparentGravityFromKinectAccel(
                                         ReadFakenectAccel((fs::path(folder) / a.file).string()))});
    accelerometer_ = AccelerometerTrack(std::move(readings));
  }
}

std::optional<Frame> FakenectSource::Next() {
  if (next_ >= pairs_.size()) return std::nullopt;
  const auto& [color, depth] = pairs_[next_];
  Frame f;
  f.index = static_cast<int>(next_);
  f.timestamp = depth.seconds;  // the pose comes from the depth image (frame.hpp)
  f.color_timestamp = color.seconds;
  f.name = color.file;
  if (options_.accelerometer) f.gravity_in_cam = accelerometer_.GravityAt(color.seconds);
  f.bgr = ReadFakenectColor((fs::path(folder_) / color.file).string());
  f.depth_m = DepthFromKinectRaw(ReadFakenectDepth((fs::path(folder_) / depth.file).string()));
  ++next_;
  return f;
}

bool FakenectSource::Skip() {
  if (next_ >= pairs_.size()) return false;
  ++next_;
  return true;
}

std::vector<std::string> FakenectSource::Files() const {
  std::vector<std::string> files;
  files.reserve(2 * pairs_.size());
  for (const auto& [color, depth] : pairs_) {
    files.push_back((fs::path(folder_) / color.file).string());
    files.push_back((fs::path(folder_) / depth.file).string());
  }
  return files;
}

std::string FakenectSource::Describe() const {
  std::ostringstream s;
  s << "fakenect recording " << folder_ << ": " << pairs_.size() << " colour-depth pairs within "
    << options_.max_time_diff_s << " s of the " << (by_device_clock_ ? "device's" : "host's")
    << " clock" << (options_.pairing == Pairing::kOneToOne ? ", one to one" : "") << " ("
    << color_frames_ << " colour, " << depth_frames_ << " depth, " << accel_entries_
    << " accelerometer entries, " << unpaired_
    << " colour frames without depth), Kinect raw 11-bit depth"
    << (has_index_ ? "" : "; no INDEX.txt: files taken in wall-clock order");
  return s.str();
}

}  // namespace rgbdvo
