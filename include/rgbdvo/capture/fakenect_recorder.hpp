#pragma once
// Writes a recording in the libfreenect "fakenect" layout (fakenect_files.hpp), one frame at a
// time, so that it replays through Debian's `fakenect` and through `rgbdvo run`.
// Each file is complete and closed before its INDEX.txt line is written and flushed, so a
// recording cut short (Ctrl-C, device lost, crash) lists only complete files.

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

namespace rgbdvo {

class FakenectRecorder {
 public:
  // Creates `folder` (and its parents). Refuses, throwing std::runtime_error naming the
  // folder, when it exists and is not empty: a recording is never overwritten.
  explicit FakenectRecorder(const std::string& folder);

  // RGB bytes (width*height*3), raw 11-bit depth (width*height values), raw accelerometer
  // state. `wallclock_us` is the host time of arrival, `device_ts` the device's timestamp.
  // Throw std::runtime_error naming the file on a write failure.
  void AddColor(int64_t wallclock_us, uint32_t device_ts, const uint8_t* rgb, int width,
                int height);
  void AddDepth(int64_t wallclock_us, uint32_t device_ts, const uint16_t* raw, int width,
                int height);
  void AddAccel(int64_t wallclock_us, uint32_t device_ts, const void* state, size_t bytes);

  const std::string& folder() const { return folder_; }
  int entries() const { return entries_; }

 private:
  std::string Path(const std::string& name) const;
  void Index(const std::string& name);
  std::string folder_;
  std::unique_ptr<FILE, int (*)(FILE*)> index_;
  int entries_ = 0;
};

}  // namespace rgbdvo
