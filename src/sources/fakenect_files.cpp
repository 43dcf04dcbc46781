#include "rgbdvo/sources/fakenect_files.hpp"

#include <libfreenect.h>

#include <cctype>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

bool AllDigits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

// "1700000000.033333" -> microseconds, exactly (no floating point on the way).
std::optional<int64_t> ParseSeconds(const std::string& s) {
  const size_t dot = s.find('.');
  const std::string whole = s.substr(0, dot);
  std::string frac = dot == std::string::npos ? "" : s.substr(dot + 1);
  if (!AllDigits(whole) || whole.size() > 12) return std::nullopt;
  if (dot != std::string::npos && !AllDigits(frac)) return std::nullopt;
  const bool round_up = frac.size() > 6 && frac[6] >= '5';
  frac.resize(6, '0');
  return std::stoll(whole) * 1000000 + std::stoll(frac) + (round_up ? 1 : 0);
}

std::string ReadWholeFile(const std::string& path, const char* what) {
  InputFileSize(path, what);  // a FIFO would block the open
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open " + what + " (missing?)");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct PnmHeader {
  std::string magic;
  int width = 0, height = 0, maxval = 0;
  size_t data_offset = 0;
};

// Header tokens separated by whitespace ('#' comments allowed), one whitespace byte before
// the data (Netpbm). fakenect's own files have the whole header on the first line.
PnmHeader ParsePnmHeader(const std::string& bytes, const std::string& path) {
  PnmHeader h;
  size_t pos = 0;
  std::string tokens[4];
  for (std::string& token : tokens) {
    for (;;) {
      while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
      if (pos < bytes.size() && bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
        continue;
      }
      break;
    }
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos])))
      token += bytes[pos++];
    if (token.empty()) throw std::runtime_error(path + ": truncated or empty PNM header");
  }
  h.magic = tokens[0];
  if (!AllDigits(tokens[1]) || !AllDigits(tokens[2]) || !AllDigits(tokens[3]) ||
      tokens[1].size() > 6 || tokens[2].size() > 6 || tokens[3].size() > 6)
    throw std::runtime_error(path + ": malformed PNM header");
  h.width = std::stoi(tokens[1]);
  h.height = std::stoi(tokens[2]);
  h.maxval = std::stoi(tokens[3]);
  if (pos >= bytes.size()) throw std::runtime_error(path + ": truncated (no image data)");
  h.data_offset = pos + 1;
  if (h.width <= 0 || h.height <= 0) throw std::runtime_error(path + ": image size is zero");
  return h;
}

void CheckSize(const std::string& bytes, const PnmHeader& h, size_t expected,
               const std::string& path) {
  const size_t have = bytes.size() - h.data_offset;
  if (have < expected)
    throw std::runtime_error(path + ": truncated (" + std::to_string(have) + " of " +
                             std::to_string(expected) + " data bytes for " +
                             std::to_string(h.width) + "x" + std::to_string(h.height) + ")");
}

void WriteFile(const std::string& path, const std::string& header, const void* data, size_t bytes) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wbx"), &std::fclose);
  if (!f) throw std::runtime_error(path + ": cannot create (exists already, or no permission)");
  bool ok = std::fwrite(header.data(), 1, header.size(), f.get()) == header.size() &&
            (bytes == 0 || std::fwrite(data, 1, bytes, f.get()) == bytes);
  ok = std::fclose(f.release()) == 0 && ok;
  if (!ok) throw std::runtime_error(path + ": write failed (disk full?)");
}

}  // namespace

std::string FakenectName::ToString() const {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "%c-%" PRId64 ".%06" PRId64 "-%" PRIu32 ".%s", type,
                wallclock_us / 1000000, wallclock_us % 1000000, device_ts, extension.c_str());
  return buf;
}

std::optional<FakenectName> ParseFakenectName(const std::string& name) {
  if (name.size() < 7 || name[1] != '-' || (name[0] != 'r' && name[0] != 'd' && name[0] != 'a'))
    return std::nullopt;
  const size_t dash = name.find('-', 2);
  if (dash == std::string::npos) return std::nullopt;
  const size_t dot = name.find('.', dash + 1);
  if (dot == std::string::npos) return std::nullopt;
  const std::optional<int64_t> us = ParseSeconds(name.substr(2, dash - 2));
  const std::string ts = name.substr(dash + 1, dot - dash - 1);
  if (!us || !AllDigits(ts) || ts.size() > 10 || std::stoull(ts) > 0xffffffffull)
    return std::nullopt;
  FakenectName n;
  n.type = name[0];
  n.wallclock_us = *us;
  n.device_ts = static_cast<uint32_t>(std::stoull(ts));
  n.extension = name.substr(dot + 1);
  return n;
}

FakenectName MakeFakenectName(char type, int64_t wallclock_us, uint32_t device_ts) {
  FakenectName n;
  n.type = type;
  n.wallclock_us = wallclock_us;
  n.device_ts = device_ts;
  n.extension = type == 'r' ? "ppm" : type == 'd' ? "pgm" : "dump";
  return n;
}

std::vector<std::string> ReadFakenectIndex(const std::string& path) {
  std::istringstream in(ReadTextFile(path, "index file", kMaxListFileBytes));
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    const size_t last = line.find_last_not_of(" \t\r");
    names.push_back(line.substr(first, last - first + 1));
  }
  return names;
}

cv::Mat ReadFakenectColor(const std::string& path) {
  const std::string bytes = ReadWholeFile(path, "colour image");
  const PnmHeader h = ParsePnmHeader(bytes, path);
  if (h.magic != "P6" || h.maxval != 255)
    throw std::runtime_error(path + ": expected an 8-bit colour PPM (P6, maxval 255), got " +
                             h.magic + " maxval " + std::to_string(h.maxval));
  CheckSize(bytes, h, static_cast<size_t>(h.width) * h.height * 3, path);
  const cv::Mat rgb(h.height, h.width, CV_8UC3, const_cast<char*>(bytes.data() + h.data_offset));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

Eigen::Vector3d ReadFakenectAccel(const std::string& path) {
  const std::string bytes = ReadWholeFile(path, "accelerometer entry");
  freenect_raw_tilt_state state{};
  if (bytes.size() != sizeof(state))
    throw std::runtime_error(
        path + ": an accelerometer entry must be " + std::to_string(sizeof(state)) +
        " bytes (freenect_raw_tilt_state), not " + std::to_string(bytes.size()));
  std::memcpy(&state, bytes.data(), sizeof(state));
  return KinectAccelFromCounts(state.accelerometer_x, state.accelerometer_y, state.accelerometer_z);
}

cv::Mat ReadFakenectDepth(const std::string& path) {
  const std::string bytes = ReadWholeFile(path, "depth image");
  const PnmHeader h = ParsePnmHeader(bytes, path);
  if (h.magic != "P5" || h.maxval < 256)
    throw std::runtime_error(path + ": expected a 16-bit depth PGM (P5, maxval 65535), got " +
                             h.magic + " maxval " + std::to_string(h.maxval));
  CheckSize(bytes, h, static_cast<size_t>(h.width) * h.height * 2, path);
  cv::Mat raw(h.height, h.width, CV_16UC1);
  const auto* in = reinterpret_cast<const uint8_t*>(bytes.data() + h.data_offset);
  for (int v = 0; v < h.height; ++v) {
    uint16_t* out = raw.ptr<uint16_t>(v);
    for (int u = 0; u < h.width; ++u, in += 2) out[u] = static_cast<uint16_t>(in[0] | in[1] << 8);
  }
  return raw;
}

void WriteFakenectColor(const std::string& path, const uint8_t* rgb, int width, int height) {
  const std::string header =
      "P6 " + std::to_string(width) + " " + std::to_string(height) + " 255\n";
  WriteFile(path, header, rgb, static_cast<size_t>(width) * height * 3);
}

void WriteFakenectDepth(const std::string& path, const uint16_t* raw, int width, int height) {
  const std::string header =
      "P5 " + std::to_string(width) + " " + std::to_string(height) + " 65535\n";
  const size_t n = static_cast<size_t>(width) * height;
  std::string le(2 * n, '\0');  // little-endian whatever the host order
  for (size_t i = 0; i < n; ++i) {
    le[2 * i] = static_cast<char>(raw[i] & 0xff);
    le[2 * i + 1] = static_cast<char>(raw[i] >> 8);
  }
  WriteFile(path, header, le.data(), le.size());
}

void WriteFakenectDump(const std::string& path, const void* data, size_t bytes) {
  WriteFile(path, "", data, bytes);
}

}  // namespace rgbdvo
