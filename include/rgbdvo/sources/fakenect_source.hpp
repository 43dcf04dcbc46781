#pragma once
// Recordings in the libfreenect "fakenect" layout (see fakenect_files.hpp): made by
// `rgbdvo capture --record`, by libfreenect's fakenect-record, and the NYU Depth V2 raw
// scenes. Depth is the Kinect's raw 11-bit disparity in the IR camera (unregistered), turned
// into metres by kinect_depth.hpp; the calibration's A/B/C/D and K_ir map colour pixels into it.

#include <string>
#include <vector>

#include "rgbdvo/sources/accelerometer_track.hpp"
#include "rgbdvo/sources/frame_source.hpp"
#include "rgbdvo/sources/pairing.hpp"

namespace rgbdvo {

struct FakenectSourceOptions {
  // Colour-depth pairing window, s: one frame period at 30 Hz. On a healthy stream the nearest
  // depth frame is at most half a period away; the rest absorbs late callbacks.
  double max_time_diff_s = 0.034;
  Pairing pairing = Pairing::kNearest;  // stream_pairer.hpp; kOneToOne uses each depth frame once
  // Read the a- entries (required then) and give each frame its gravity (Frame::gravity_in_cam).
  bool accelerometer = false;
  void Check() const;
};

// True when `folder` holds an INDEX.txt, or r-/d- frame files (some copies of NYU Depth V2 raw
// scenes come without INDEX.txt; their files are then taken in wall-clock order).
bool IsFakenectFolder(const std::string& folder);

class FakenectSource : public FrameSource {
 public:
  // Reads INDEX.txt and pairs colour and depth frames by their device timestamps, or by the
  // wall-clock times when the recording has no device timestamps (stream_pairer.hpp). Throws
  // std::runtime_error naming INDEX.txt and the line for a name not of the layout, naming the
  // first missing file (and how many are missing), or for a recording without any pair.
  FakenectSource(const std::string& folder, const FakenectSourceOptions& options);
  std::optional<Frame> Next() override;
  std::string Describe() const override;
  bool Skip() override;
  std::optional<size_t> Size() const override { return pairs_.size(); }
  std::vector<std::string> Files() const override;

  size_t size() const { return pairs_.size(); }
  int unpaired() const { return unpaired_; }  // colour frames without depth in the window

 private:
  struct Entry {
    std::string file;
    double seconds = 0;
  };
  std::string folder_;
  FakenectSourceOptions options_;
  std::vector<std::pair<Entry, Entry>> pairs_;  // colour, depth
  AccelerometerTrack accelerometer_;            // with options_.accelerometer
  bool has_index_ = true, by_device_clock_ = true;
  int color_frames_ = 0, depth_frames_ = 0, accel_entries_ = 0, unpaired_ = 0;
  size_t next_ = 0;
};

}  // namespace rgbdvo
