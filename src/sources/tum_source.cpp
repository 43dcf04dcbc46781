#include "rgbdvo/sources/tum_source.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/io/image_reader.hpp"
#include "rgbdvo/io/text.hpp"
#include "rgbdvo/sensor/depth_encoding.hpp"
#include "rgbdvo/util/display_text.hpp"

namespace fs = std::filesystem;

namespace rgbdvo {

void TumSourceOptions::Check() const {
  if (!(max_time_diff_s > 0))
    throw std::invalid_argument("TumSourceOptions.max_time_diff_s must be > 0");
  if (!(depth_units_per_m > 0))
    throw std::invalid_argument("TumSourceOptions.depth_units_per_m must be > 0");
}

std::vector<TumListEntry> ReadTumList(const std::string& path) {
  std::vector<TumListEntry> entries;
  for (const ListLine& line : ReadListLines(path, "list file")) {
    std::istringstream fields(line.text);
    TumListEntry e;
    if (!(fields >> e.timestamp >> e.path) || !std::isfinite(e.timestamp))
      throw std::runtime_error(path + ":" + std::to_string(line.number) +
                               ": expected 'timestamp path', got '" + Excerpt(line.text) + "'");
    entries.push_back(e);
  }
  return entries;
}

namespace {

bool Earlier(const TumListEntry& a, const TumListEntry& b) { return a.timestamp < b.timestamp; }

// The colour frame of a list entry or of a pair: what the time order is taken by.
// NOLINTNEXTLINE(bugprone-return-const-ref-from-parameter): only given elements of a vector
const TumListEntry& Colour(const TumListEntry& e) { return e; }
const TumListEntry& Colour(const TumPair& p) { return p.rgb; }

template <typename Item>
TimeOrderRepair PutInColourTimeOrder(std::vector<Item>* items) {
  TimeOrderRepair repair;
  for (size_t i = 1; i < items->size(); ++i)
    if (Colour((*items)[i]).timestamp < Colour((*items)[i - 1]).timestamp) ++repair.out_of_order;
  std::stable_sort(items->begin(), items->end(),
                   [](const Item& a, const Item& b) { return Earlier(Colour(a), Colour(b)); });
  std::vector<Item> kept;
  kept.reserve(items->size());
  for (Item& item : *items) {
    if (!kept.empty() && Colour(item).timestamp == Colour(kept.back()).timestamp)
      repair.repeated.push_back(Colour(item));
    else
      kept.push_back(std::move(item));
  }
  items->swap(kept);
  return repair;
}

}  // namespace

TimeOrderRepair PutInTimeOrder(std::vector<TumListEntry>* entries) {
  return PutInColourTimeOrder(entries);
}

TimeOrderRepair PutInTimeOrder(std::vector<TumPair>* pairs) { return PutInColourTimeOrder(pairs); }

bool IsTumFolder(const std::string& folder) {
  return fs::is_regular_file(fs::path(folder) / "rgb.txt") &&
         fs::is_regular_file(fs::path(folder) / "depth.txt");
}

TumSource::TumSource(const std::string& folder, const TumSourceOptions& options)
    : folder_(folder), options_(options) {
  options_.Check();
  if (!fs::is_directory(folder)) throw std::runtime_error(folder + ": no such folder");
  for (const char* list : {"rgb.txt", "depth.txt"})
    if (!fs::is_regular_file(fs::path(folder) / list))
      throw std::runtime_error(folder + ": missing " + list + " (not a TUM RGB-D folder)");
  std::vector<TumListEntry> rgb = ReadTumList((fs::path(folder) / "rgb.txt").string());
  rgb_order_ = PutInTimeOrder(&rgb);
  std::vector<TumListEntry> depth = ReadTumList((fs::path(folder) / "depth.txt").string());
  std::sort(depth.begin(), depth.end(), Earlier);
  std::vector<double> rgb_s, depth_s;
  for (const TumListEntry& r : rgb) rgb_s.push_back(r.timestamp);
  for (const TumListEntry& d : depth) depth_s.push_back(d.timestamp);
  const StampPairs paired = PairStamps(options_.pairing, rgb_s, depth_s, options_.max_time_diff_s);
  for (const StampPairs::Pair& p : paired.pairs) pairs_.push_back({rgb[p.color], depth[p.depth]});
  for (size_t c : paired.unpaired_color) unpaired_.push_back(rgb[c]);
  if (pairs_.empty())
    throw std::runtime_error(folder + ": empty sequence (" + std::to_string(rgb.size()) +
                             " rgb frames, none with a depth frame within " +
                             std::to_string(options_.max_time_diff_s) + " s)");
  ReadAccelerometer();
}

TumSource::TumSource(const std::string& folder, std::vector<TumPair> pairs,
                     const std::string& origin, const TumSourceOptions& options)
    : folder_(folder), origin_(origin), options_(options), pairs_(std::move(pairs)) {
  options_.Check();
  if (pairs_.empty()) throw std::runtime_error(origin + ": empty sequence (no pair)");
  rgb_order_ = PutInTimeOrder(&pairs_);
  ReadAccelerometer();
}

void TumSource::ReadAccelerometer() {
  if (!options_.accelerometer) return;
  const std::string path = (fs::path(folder_) / "accelerometer.txt").string();
  if (!fs::is_regular_file(path))
    throw std::runtime_error(folder_ + ": no accelerometer.txt (accelerometer readings needed)");
  accelerometer_ = AccelerometerTrack(ReadTumAccelerometer(path));
  if (accelerometer_.size() == 0) throw std::runtime_error(path + ": no reading");
}

std::optional<Frame> TumSource::Next() {
  if (next_ >= pairs_.size()) return std::nullopt;
  const TumPair& p = pairs_[next_];
  const std::string rgb_path = (fs::path(folder_) / p.rgb.path).string();
  const std::string depth_path = (fs::path(folder_) / p.depth.path).string();
  Frame f;
  f.index = static_cast<int>(next_);
  f.timestamp = p.depth.timestamp;
  f.color_timestamp = p.rgb.timestamp;
  f.name = p.rgb.path;
  if (options_.accelerometer) f.gravity_in_cam = accelerometer_.GravityAt(f.color_timestamp);
  f.bgr = ReadImage(rgb_path, cv::IMREAD_COLOR);
  if (f.bgr.empty())
    throw std::runtime_error(rgb_path +
                             ": cannot read colour image (missing, corrupt or truncated)");
  const cv::Mat raw = ReadImage(depth_path, cv::IMREAD_UNCHANGED);
  if (raw.empty())
    throw std::runtime_error(depth_path +
                             ": cannot read depth image (missing, corrupt or truncated)");
  if (raw.type() != CV_16UC1)
    throw std::runtime_error(depth_path + ": depth image must be 16-bit single channel");
  if (raw.size() != f.bgr.size())
    throw std::runtime_error(depth_path + ": depth image is " + std::to_string(raw.cols) + "x" +
                             std::to_string(raw.rows) + " but colour image " + rgb_path + " is " +
                             std::to_string(f.bgr.cols) + "x" + std::to_string(f.bgr.rows));
  f.depth_m = DepthFromScaled16(raw, options_.depth_units_per_m);
  ++next_;
  return f;
}

bool TumSource::Skip() {
  if (next_ >= pairs_.size()) return false;
  ++next_;
  return true;
}

std::vector<std::string> TumSource::Files() const {
  std::vector<std::string> files;
  files.reserve(2 * pairs_.size());
  for (const TumPair& p : pairs_) {
    files.push_back((fs::path(folder_) / p.rgb.path).string());
    files.push_back((fs::path(folder_) / p.depth.path).string());
  }
  return files;
}

std::string TumSource::rgb_list() const {
  return origin_.empty() ? (fs::path(folder_) / "rgb.txt").string() : origin_;
}

std::string TumSource::Describe() const {
  std::ostringstream s;
  if (!origin_.empty()) {
    s << "association file " << origin_ << ": " << pairs_.size()
      << " rgb-depth pairs as the file pairs them, in time order, "
      << "depth " << options_.depth_units_per_m << " units per metre";
    if (options_.accelerometer) s << ", " << accelerometer_.size() << " accelerometer readings";
    return s.str();
  }
  s << "TUM RGB-D folder " << folder_ << ": " << pairs_.size() << " rgb-depth pairs within "
    << options_.max_time_diff_s << " s"
    << (options_.pairing == Pairing::kOneToOne ? " (one to one)" : "") << ", " << unpaired_.size()
    << " rgb frames without depth, "
    << "depth " << options_.depth_units_per_m << " units per metre";
  if (options_.accelerometer) s << ", " << accelerometer_.size() << " accelerometer readings";
  return s.str();
}

}  // namespace rgbdvo
