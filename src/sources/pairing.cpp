#include "rgbdvo/sources/pairing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace rgbdvo {

Pairing ParsePairing(const std::string& name) {
  if (name == "nearest") return Pairing::kNearest;
  if (name == "one-to-one") return Pairing::kOneToOne;
  throw std::invalid_argument("unknown pairing '" + name + "' (expected nearest or one-to-one)");
}

std::string PairingName(Pairing pairing) {
  return pairing == Pairing::kOneToOne ? "one-to-one" : "nearest";
}

namespace {

// The depth stamps within max_dt_s of t: [first, last).
std::pair<size_t, size_t> Window(const std::vector<double>& depth_s, double t, double max_dt_s) {
  const auto first = std::lower_bound(depth_s.begin(), depth_s.end(), t - max_dt_s);
  const auto last = std::upper_bound(first, depth_s.end(), t + max_dt_s);
  return {static_cast<size_t>(first - depth_s.begin()),
          static_cast<size_t>(last - depth_s.begin())};
}

StampPairs PairNearest(const std::vector<double>& color_s, const std::vector<double>& depth_s,
                       double max_dt_s) {
  StampPairs out;
  for (size_t c = 0; c < color_s.size(); ++c) {
    const double t = color_s[c];
    const auto after = std::lower_bound(depth_s.begin(), depth_s.end(), t);
    auto best = after;
    if (after != depth_s.begin() && (after == depth_s.end() || t - *(after - 1) < *after - t))
      best = after - 1;
    if (best != depth_s.end() && std::abs(*best - t) <= max_dt_s)
      out.pairs.push_back({c, static_cast<size_t>(best - depth_s.begin())});
    else
      out.unpaired_color.push_back(c);
  }
  return out;
}

// associate.py: all candidates sorted by (|dt|, colour time, depth time), taken greedily.
StampPairs PairOneToOne(const std::vector<double>& color_s, const std::vector<double>& depth_s,
                        double max_dt_s) {
  std::vector<std::tuple<double, double, double, size_t, size_t>> candidates;
  for (size_t c = 0; c < color_s.size(); ++c) {
    const auto [first, last] = Window(depth_s, color_s[c], max_dt_s);
    for (size_t d = first; d < last; ++d)
      candidates.emplace_back(std::abs(color_s[c] - depth_s[d]), color_s[c], depth_s[d], c, d);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> color_used(color_s.size(), false), depth_used(depth_s.size(), false);
  std::vector<long> depth_of(color_s.size(), -1);
  for (const auto& candidate : candidates) {
    const size_t c = std::get<3>(candidate), d = std::get<4>(candidate);
    if (color_used[c] || depth_used[d]) continue;
    color_used[c] = depth_used[d] = true;
    depth_of[c] = static_cast<long>(d);
  }
  StampPairs out;
  for (size_t c = 0; c < color_s.size(); ++c) {
    if (depth_of[c] >= 0)
      out.pairs.push_back({c, static_cast<size_t>(depth_of[c])});
    else
      out.unpaired_color.push_back(c);
  }
  return out;
}

}  // namespace

StampPairs PairStamps(Pairing pairing, const std::vector<double>& color_s,
                      const std::vector<double>& depth_s, double max_dt_s) {
  if (!std::is_sorted(depth_s.begin(), depth_s.end()))
    throw std::invalid_argument("PairStamps: depth stamps must be ascending");
  return pairing == Pairing::kOneToOne ? PairOneToOne(color_s, depth_s, max_dt_s)
                                       : PairNearest(color_s, depth_s, max_dt_s);
}

}  // namespace rgbdvo
