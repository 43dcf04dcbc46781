#pragma once
// Pairs a stream of colour frames with the nearest depth frame in time, online, as frames
// arrive in one stream (a live device or the lines of a fakenect INDEX.txt). Both the live
// capture and the recording reader use it, so a recording replays into the same pairs.
// The times are the Kinect's own frame timestamps (KinectClock below), not the host's arrival
// times, which a busy host delays by different amounts for the two streams.
//
// Rule: a colour frame waits for the next depth frame, then takes whichever of the depth frame
// before it and the one after it is nearer in time (the earlier on a tie), if within
// max_dt_us. A colour frame still waiting when the next colour frame arrives is decided with
// the depth frame before it only, so at most one colour frame and one depth frame are held.

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <utility>
#include <vector>

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
class StreamPairer {
 public:
  explicit StreamPairer(int64_t max_dt_us) : max_dt_us_(max_dt_us) {}

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

}  // namespace rgbdvo
