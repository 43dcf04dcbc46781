#pragma once
// The libfreenect "fakenect" recording layout (written by fakenect-record, replayed by the
// fakenect library; also used by the NYU Depth V2 raw scenes):
//   INDEX.txt        one file name per line, in the order the frames arrived
//   r-<wallclock>-<devicets>.ppm   colour: "P6 <w> <h> 255\n" then w*h RGB bytes
//   d-<wallclock>-<devicets>.pgm   depth: "P5 <w> <h> 65535\n" then w*h 16-bit raw values,
//                                  little-endian (the host order of the recorder, not the
//                                  big-endian order of the PGM standard)
//   a-<wallclock>-<devicets>.dump  accelerometer: a raw freenect_raw_tilt_state
// <wallclock> is the host time in seconds with 6 decimals ("%f"), <devicets> the device's
// 32-bit frame timestamp. fakenect parses both from the name and needs the header on one line.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rgbdvo {

struct FakenectName {
  char type = 0;             // 'r' colour, 'd' depth, 'a' accelerometer
  int64_t wallclock_us = 0;  // host time, microseconds
  uint32_t device_ts = 0;    // device frame timestamp
  std::string extension;     // "ppm", "pgm", "dump"
  double seconds() const { return static_cast<double>(wallclock_us) * 1e-6; }
  std::string ToString() const;  // "r-1700000000.033333-2000.ppm"
};

// nullopt when `name` is not <type>-<seconds>-<devicets>.<ext> with type r, d or a.
std::optional<FakenectName> ParseFakenectName(const std::string& name);
// A name with the extension fakenect expects for `type`.
FakenectName MakeFakenectName(char type, int64_t wallclock_us, uint32_t device_ts);

// The file names listed in INDEX.txt, in order: trailing CR and surrounding blanks removed,
// blank lines skipped. Throws std::runtime_error naming the file if it cannot be read.
std::vector<std::string> ReadFakenectIndex(const std::string& path);

// Colour: returns CV_8UC3 in BGR order. Depth: returns CV_16UC1 raw values. Both throw
// std::runtime_error naming the file when it is missing, of the wrong kind or truncated.
cv::Mat ReadFakenectColor(const std::string& path);
cv::Mat ReadFakenectDepth(const std::string& path);
// An a- entry (a freenect_raw_tilt_state): the accelerometer's reading in m/s^2 (libfreenect's
// axes, kinect_accelerometer.hpp). Throws std::runtime_error naming the file when it is missing
// or not of the state's size.
Eigen::Vector3d ReadFakenectAccel(const std::string& path);

// Write one image in the layout above (header on one line, then the bytes). `rgb` is
// width*height*3 bytes in RGB order; `raw` is width*height 16-bit values. The file is complete
// and closed when the call returns; throws std::runtime_error naming the file on failure.
void WriteFakenectColor(const std::string& path, const uint8_t* rgb, int width, int height);
void WriteFakenectDepth(const std::string& path, const uint16_t* raw, int width, int height);
void WriteFakenectDump(const std::string& path, const void* data, size_t bytes);

}  // namespace rgbdvo
