#pragma once
// A TUM RGB-D folder written as a ROS 2 bag, laid out as the TUM bags are (rgb8 colour on
// /camera/rgb/image_color, depth on /camera/depth/image, camera_info beside each), serialised
// as CDR: for reading recordings of our own as ROS 2 bags, in the tests and for users.

#include <cstddef>
#include <limits>
#include <string>

namespace rgbdvo {

struct TumToRos2Options {
  std::string storage = "mcap";          // "mcap" (.mcap file) or "sqlite3" (.db3 file)
  std::string compression = "zstd";      // MCAP chunks: "", "zstd" or "lz4"
  std::string depth_encoding = "32FC1";  // 32FC1 metres (the folder's depth exactly) or 16UC1 mm
  bool camera_info = true;               // camera_info on both image topics' siblings
  double fx = 525, fy = 525, cx = 319.5, cy = 239.5;  // its K (the TUM bags'), pixels
  // The folder's frames written: from `first`, at most `count` (a part of a split bag).
  size_t first = 0, count = std::numeric_limits<size_t>::max();
  void Check() const;  // throws, naming the field and the rule it broke
};

// Writes the folder's frames (TumSource's pairs, each colour and depth image with its own
// stamp, in stamp order) to `out`; returns how many. Throws std::runtime_error naming the
// folder or the file.
size_t WriteTumAsRos2Bag(const std::string& folder, const std::string& out,
                         const TumToRos2Options& options);

}  // namespace rgbdvo
