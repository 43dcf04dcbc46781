#pragma once
// TUM RGB-D folders: rgb.txt, depth.txt, rgb/*.png, depth/*.png (Sturm et al. 2012).

#include <string>
#include <vector>

#include "rgbdvo/sources/accelerometer_track.hpp"
#include "rgbdvo/sources/frame_source.hpp"
#include "rgbdvo/sources/pairing.hpp"

namespace rgbdvo {

struct TumSourceOptions {
  double max_time_diff_s = 0.02;        // rgb/depth association window (TUM tools: 0.02 s)
  double depth_units_per_m = 5000.;     // 16-bit depth scale (TUM: 5000 per metre)
  Pairing pairing = Pairing::kNearest;  // pairing.hpp; kOneToOne as associate.py
  // Read accelerometer.txt (required then) and give each frame its gravity (Frame::gravity_in_cam).
  bool accelerometer = false;
  void Check() const;
};

// One `timestamp path` line of a TUM list file.
struct TumListEntry {
  double timestamp = 0;
  std::string path;  // relative to the folder
};

// A colour image and the depth image it is paired with.
struct TumPair {
  TumListEntry rgb, depth;
};

// Reads rgb.txt / depth.txt style lists: '#' comments and blank lines skipped, CRLF tolerated.
// Throws std::runtime_error naming the file and line for unreadable files or malformed lines.
std::vector<TumListEntry> ReadTumList(const std::string& path);

// What putting a colour list in time order changed (a list concatenated or edited by hand).
struct TimeOrderRepair {
  size_t out_of_order = 0;             // lines whose timestamp is below the line's before
  std::vector<TumListEntry> repeated;  // lines dropped: their timestamp is an earlier line's
};
// Sorts `entries` by timestamp (stable) and keeps the first of each timestamp: every pose gets a
// distinct, increasing stamp, as trajectory formats and evaluation tools require.
TimeOrderRepair PutInTimeOrder(std::vector<TumListEntry>* entries);
// The same for an association file's pairs, by their colour frame's timestamp (`repeated` holds
// the colour entries of the pairs dropped).
TimeOrderRepair PutInTimeOrder(std::vector<TumPair>* pairs);

// True when `folder` has the TUM layout (rgb.txt and depth.txt).
bool IsTumFolder(const std::string& folder);

class TumSource : public FrameSource {
 public:
  // Throws std::runtime_error naming the missing folder or list file, or an empty sequence.
  TumSource(const std::string& folder, const TumSourceOptions& options);
  // The pairs as given (an association file's, association_file.hpp), put in time order by
  // their colour frames (PutInTimeOrder), paths relative to `folder`; `origin` names where they
  // came from (for Describe). Throws for an empty list.
  TumSource(const std::string& folder, std::vector<TumPair> pairs, const std::string& origin,
            const TumSourceOptions& options);
  std::optional<Frame> Next() override;
  std::string Describe() const override;
  bool Skip() override;
  std::optional<size_t> Size() const override { return pairs_.size(); }
  std::vector<std::string> Files() const override;

  size_t size() const { return pairs_.size(); }
  const std::string& folder() const { return folder_; }
  // Colour frames with no depth frame within the window, or (one-to-one) whose candidates were
  // all taken by closer pairs (reported, then skipped).
  const std::vector<TumListEntry>& unpaired() const { return unpaired_; }
  // What PutInTimeOrder changed in the list of colour frames (reported, then taken in time
  // order), and that list's file: rgb.txt or the association file.
  const TimeOrderRepair& rgb_order() const { return rgb_order_; }
  std::string rgb_list() const;

 private:
  std::string folder_;
  std::string origin_;  // an association file, or empty: rgb.txt and depth.txt
  TumSourceOptions options_;
  std::vector<TumPair> pairs_;
  std::vector<TumListEntry> unpaired_;
  TimeOrderRepair rgb_order_;
  AccelerometerTrack accelerometer_;  // with options_.accelerometer
  size_t next_ = 0;
  void ReadAccelerometer();
};

}  // namespace rgbdvo
