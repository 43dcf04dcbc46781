#pragma once
// Pairs a stream of colour frames with the nearest depth frame in time, online, as frames
// arrive in one stream (a live device or the lines of a fakenect INDEX.txt). Both the live
// capture and the recording reader use it, so a recording replays into the same pairs.
// The times are the Kinect's own frame timestamps (KinectClock below), not the host's arrival
// times, which a busy host delays by different amounts for the two streams.
//
// Pairing::kNearest: a colour frame waits for the next depth frame, then takes whichever of the
// depth frame before it and the one after it is nearer in time (the earlier on a tie), if
// within max_dt_us. A colour frame still waiting when the next colour frame arrives is decided
// with the depth frame before it only, so at most one colour frame and one depth frame are held.
//
// Pairing::kOneToOne: associate.py's rule (pairing.hpp: closest pairs first, each frame used
// once) online. The closest pair among the frames held is taken once no frame yet to come could
// be closer to either of its frames: each stream's stamps ascend, so a colour frame to come is
// at least (latest colour time - depth time) from the depth frame, and likewise for depth. On
// streams in time order this gives exactly associate.py's pairs over the whole recording, each
// decided about one frame period late. A colour frame is dropped when no depth frame held or to
// come can pair with it. At most kMaxHeld colour frames wait (a stalled depth stream): beyond,
// the oldest takes its nearest free depth frame at hand, or is dropped.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "rgbdvo/sources/pairing.hpp"

namespace rgbdvo {

// The Kinect v1 stamps colour and depth frames with one 32-bit 60 MHz counter (libfreenect
// issue #681; frames within about 2 ms belong together). It wraps every 71.6 s; this unwraps a
// sequence of stamps into microseconds since the first, assuming consecutive stamps (of
// either stream) are less than 35 s apart.
class KinectClock {
 public:
  static constexpr double kTicksPerMicrosecond = 60.0;
  int64_t Micros(uint32_t stamp) {
    if (!started_) {
      started_ = true;
      last_ = stamp;
    }
    ticks_ += static_cast<int32_t>(stamp - last_);  // signed difference, modulo 2^32
    last_ = stamp;
    return static_cast<int64_t>(std::llround(static_cast<double>(ticks_) / kTicksPerMicrosecond));
  }
  // A device time (Micros) on the host's clock: the first call's host time plus the device time
  // since. Host arrival times jitter by tens of milliseconds on a busy host, differently for
  // colour and depth; the device clock does not, so frames are stamped with this.
  int64_t OnHost(int64_t device_us, int64_t host_us) {
    if (!anchored_) {
      host_minus_device_us_ = host_us - device_us;
      anchored_ = true;
    }
    return host_minus_device_us_ + device_us;
  }

 private:
  bool started_ = false;
  uint32_t last_ = 0;
  int64_t ticks_ = 0;
  bool anchored_ = false;
  int64_t host_minus_device_us_ = 0;
};

template <class T>
struct Stamped {
  int64_t t_us = 0;
  T value;
};

template <class T>
struct StampedPair {
  Stamped<T> color, depth;
};

template <class T>
class NearestStreamPairer {
 public:
  explicit NearestStreamPairer(int64_t max_dt_us) : max_dt_us_(max_dt_us) {}

  // Each returns the pairs this frame completes (zero, one or two), in colour order.
  std::vector<StampedPair<T>> AddColor(Stamped<T> color) {
    std::vector<StampedPair<T>> out;
    if (has_pending_) Decide(nullptr, &out);
    pending_ = std::move(color);
    has_pending_ = true;
    return out;
  }
  std::vector<StampedPair<T>> AddDepth(Stamped<T> depth) {
    std::vector<StampedPair<T>> out;
    if (has_pending_) Decide(&depth, &out);
    last_depth_ = std::move(depth);
    has_last_depth_ = true;
    return out;
  }
  // End of the stream: decides a waiting colour frame with the depth frame before it.
  std::vector<StampedPair<T>> Finish() {
    std::vector<StampedPair<T>> out;
    if (has_pending_) Decide(nullptr, &out);
    return out;
  }

  // Colour frames with no depth frame within max_dt_us (dropped).
  int unpaired() const { return unpaired_; }

 private:
  void Decide(const Stamped<T>* next_depth, std::vector<StampedPair<T>>* out) {
    const Stamped<T>* best = nullptr;
    int64_t best_dt = 0;
    const Stamped<T>* before = has_last_depth_ ? &last_depth_ : nullptr;
    for (const Stamped<T>* d : {before, next_depth}) {
      if (!d) continue;
      const int64_t dt = std::llabs(d->t_us - pending_.t_us);
      if (dt <= max_dt_us_ && (!best || dt < best_dt)) best = d, best_dt = dt;
    }
    if (best)
      out->push_back({std::move(pending_), *best});
    else
      ++unpaired_;
    has_pending_ = false;
  }

  int64_t max_dt_us_;
  bool has_pending_ = false, has_last_depth_ = false;
  Stamped<T> pending_, last_depth_;
  int unpaired_ = 0;
};

template <class T>
class OneToOneStreamPairer {
 public:
  static constexpr size_t kMaxHeld = 8;
  explicit OneToOneStreamPairer(int64_t max_dt_us) : max_dt_us_(max_dt_us) {}

  std::vector<StampedPair<T>> AddColor(Stamped<T> color) {
    latest_color_ = color.t_us;
    seen_color_ = true;
    colors_.push_back({std::move(color), std::nullopt, false});
    return Resolve(false);
  }
  std::vector<StampedPair<T>> AddDepth(Stamped<T> depth) {
    latest_depth_ = depth.t_us;
    seen_depth_ = true;
    depths_.push_back(std::move(depth));
    if (depths_.size() > 2 * kMaxHeld) depths_.pop_front();  // a stalled colour stream
    return Resolve(false);
  }
  std::vector<StampedPair<T>> Finish() { return Resolve(true); }
  int unpaired() const { return unpaired_; }

 private:
  struct Held {
    Stamped<T> color;
    std::optional<Stamped<T>> depth;
    bool decided = false;
  };
  using Key = std::tuple<int64_t, int64_t, int64_t>;  // |dt|, colour time, depth time

  bool Near(int64_t a, int64_t b) const { return std::llabs(a - b) <= max_dt_us_; }
  // The closest free pair held (associate.py's order), if any: colour and depth positions.
  std::optional<std::pair<size_t, size_t>> Closest(size_t only_color = SIZE_MAX) const {
    std::optional<std::pair<size_t, size_t>> best;
    Key best_key{};
    for (size_t c = 0; c < colors_.size(); ++c) {
      if (colors_[c].decided || (only_color != SIZE_MAX && c != only_color)) continue;
      for (size_t d = 0; d < depths_.size(); ++d) {
        const int64_t tc = colors_[c].color.t_us, td = depths_[d].t_us;
        const Key key{std::llabs(tc - td), tc, td};
        if (!Near(tc, td) || (best && !(key < best_key))) continue;
        best = std::make_pair(c, d);
        best_key = key;
      }
    }
    return best;
  }
  // No frame to come can be closer to either frame of the pair (stamps ascend per stream).
  bool Final(size_t c, size_t d, bool end) const {
    const int64_t tc = colors_[c].color.t_us, td = depths_[d].t_us, dt = std::llabs(tc - td);
    return end || (latest_color_ - td >= dt && latest_depth_ - tc >= dt);
  }
  void Take(size_t c, size_t d) {
    colors_[c].depth = std::move(depths_[d]);
    colors_[c].decided = true;
    depths_.erase(depths_.begin() + static_cast<std::ptrdiff_t>(d));
  }
  // Drops colour frames no depth frame held or to come can pair with, and depth frames no
  // colour frame can.
  void Prune(bool end) {
    for (Held& h : colors_) {
      if (h.decided) continue;
      bool candidate = false;
      for (const Stamped<T>& d : depths_) candidate = candidate || Near(h.color.t_us, d.t_us);
      const bool more = !end && (!seen_depth_ || latest_depth_ - h.color.t_us <= max_dt_us_);
      if (!candidate && !more) h.decided = true, ++unpaired_;
    }
    for (size_t d = 0; d < depths_.size();) {
      bool candidate = false;
      for (const Held& h : colors_)
        candidate = candidate || (!h.decided && Near(h.color.t_us, depths_[d].t_us));
      const bool more = !end && (!seen_color_ || latest_color_ - depths_[d].t_us <= max_dt_us_);
      if (!candidate && !more)
        depths_.erase(depths_.begin() + static_cast<std::ptrdiff_t>(d));
      else
        ++d;
    }
  }
  std::vector<StampedPair<T>> Resolve(bool end) {
    for (;;) {
      const auto best = Closest();
      if (!best || !Final(best->first, best->second, end)) break;
      Take(best->first, best->second);
    }
    Prune(end);
    while (colors_.size() > kMaxHeld && !colors_.front().decided) {  // forced, see above
      if (const auto best = Closest(0))
        Take(best->first, best->second);
      else
        colors_.front().decided = true, ++unpaired_;
    }
    std::vector<StampedPair<T>> out;
    while (!colors_.empty() && colors_.front().decided) {
      if (colors_.front().depth)
        out.push_back({std::move(colors_.front().color), std::move(*colors_.front().depth)});
      colors_.pop_front();
    }
    return out;
  }

  int64_t max_dt_us_;
  std::deque<Held> colors_;        // in arrival order, until emitted
  std::deque<Stamped<T>> depths_;  // free depth frames that may still be paired
  bool seen_color_ = false, seen_depth_ = false;
  int64_t latest_color_ = 0, latest_depth_ = 0;
  int unpaired_ = 0;
};

// Either rule behind one interface; the pairs come out in colour order.
template <class T>
class StreamPairer {
 public:
  explicit StreamPairer(int64_t max_dt_us, Pairing pairing = Pairing::kNearest)
      : one_to_one_(pairing == Pairing::kOneToOne), nearest_(max_dt_us), unique_(max_dt_us) {}
  // Each returns the pairs this frame completes (zero or more), in colour order.
  std::vector<StampedPair<T>> AddColor(Stamped<T> color) {
    return one_to_one_ ? unique_.AddColor(std::move(color)) : nearest_.AddColor(std::move(color));
  }
  std::vector<StampedPair<T>> AddDepth(Stamped<T> depth) {
    return one_to_one_ ? unique_.AddDepth(std::move(depth)) : nearest_.AddDepth(std::move(depth));
  }
  // End of the stream: decides the colour frames still waiting.
  std::vector<StampedPair<T>> Finish() {
    return one_to_one_ ? unique_.Finish() : nearest_.Finish();
  }
  // Colour frames dropped: no depth frame within max_dt_us (one-to-one: none left free).
  int unpaired() const { return one_to_one_ ? unique_.unpaired() : nearest_.unpaired(); }

 private:
  bool one_to_one_;
  NearestStreamPairer<T> nearest_;
  OneToOneStreamPairer<T> unique_;
};

}  // namespace rgbdvo
