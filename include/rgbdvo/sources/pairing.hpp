#pragma once
// Pairing colour images with depth images taken at slightly different times, over whole lists
// of stamps (a TUM folder's rgb.txt and depth.txt). stream_pairer.hpp does the same online.

#include <cstddef>
#include <string>
#include <vector>

namespace rgbdvo {

enum class Pairing {
  // Each colour image takes the nearest depth image in time; two colour images can share one
  // depth image (and, stamped by it, one timestamp). Every colour image with a depth image
  // within the window is kept.
  kNearest,
  // As the TUM tools' associate.py: every (colour, depth) pair within the window, closest pairs
  // first, each colour and each depth image used at most once. A colour image whose candidates
  // were all taken by closer pairs is dropped.
  kOneToOne,
};

// "nearest" or "one-to-one"; throws std::invalid_argument naming the value.
Pairing ParsePairing(const std::string& name);
std::string PairingName(Pairing pairing);

struct StampPairs {
  struct Pair {
    size_t color = 0, depth = 0;  // indices into the stamp lists
  };
  std::vector<Pair> pairs;             // in colour order
  std::vector<size_t> unpaired_color;  // colour images left without a depth image, in order
};

// Pairs colour stamps (in their order) with depth stamps (ascending), seconds, within
// max_dt_s (inclusive). kNearest takes the later depth image on a tie; kOneToOne orders pairs
// as associate.py does (by time difference, then colour time, then depth time).
StampPairs PairStamps(Pairing pairing, const std::vector<double>& color_s,
                      const std::vector<double>& depth_s, double max_dt_s);

}  // namespace rgbdvo
