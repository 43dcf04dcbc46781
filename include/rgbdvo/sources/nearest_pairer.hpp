#pragma once
// Pairs colour and depth images that arrive as a stream (the messages of a bag, in record
// order) by the rule TumSource applies to a folder's two lists: each colour image takes the
// depth image nearest in time (the later one on a tie), if within max_dt_s; a depth image may
// serve two colour images. Online: a colour image is decided once a message stamped max_dt_s
// after it has arrived (or at the end), so messages may arrive out of stamp order by up to
// that much, and only the images of that span are held.

#include <cmath>
#include <deque>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

namespace rgbdvo {

template <class T>
struct TimedPair {
  double color_s = 0, depth_s = 0;
  T color, depth;
};

template <class T>
class NearestPairer {
 public:
  explicit NearestPairer(double max_dt_s) : max_dt_s_(max_dt_s) {}

  void AddColor(double t, T value) { Insert(&colors_, t, std::move(value)); }
  void AddDepth(double t, T value) { Insert(&depths_, t, std::move(value)); }

  // The pairs decided so far, in colour order; with `finished` (the end of the stream), every
  // waiting colour image is decided.
  std::vector<TimedPair<T>> Take(bool finished) {
    std::vector<TimedPair<T>> out;
    while (!colors_.empty() && (finished || latest_s_ >= colors_.front().first + max_dt_s_)) {
      const double t = colors_.front().first;
      // Depth images too early for this colour image are too early for every later one.
      while (!depths_.empty() && depths_.front().first < t - max_dt_s_) depths_.pop_front();
      const std::pair<double, T>* best = nullptr;
      for (const auto& d : depths_) {  // at most a few, in stamp order
        if (d.first > t + max_dt_s_) break;
        if (!best || std::abs(d.first - t) <= std::abs(best->first - t)) best = &d;
      }
      if (best)
        out.push_back({t, best->first, std::move(colors_.front().second), best->second});
      else
        ++unpaired_;
      colors_.pop_front();
    }
    return out;
  }

  int unpaired() const { return unpaired_; }  // colour images without depth in the window

 private:
  void Insert(std::deque<std::pair<double, T>>* queue, double t, T value) {
    auto it = queue->end();
    while (it != queue->begin() && std::prev(it)->first > t) --it;
    queue->insert(it, {t, std::move(value)});
    if (t > latest_s_) latest_s_ = t;
  }

  double max_dt_s_;
  double latest_s_ = -std::numeric_limits<double>::infinity();
  std::deque<std::pair<double, T>> colors_, depths_;
  int unpaired_ = 0;
};

}  // namespace rgbdvo
