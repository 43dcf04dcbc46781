#include "rgbdvo/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "rgbdvo/bounded_queue.hpp"

namespace rgbdvo {
namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A frame with its features, or the end of the source, or the source's exception.
struct Decoded {
  std::optional<Frame> frame;
  Features features;
  double decode_seconds = 0, feature_seconds = 0;
  std::exception_ptr error;
};

// Reads the next frame and extracts its features; never throws (the error travels in the item).
Decoded DecodeNext(FrameSource& source, const SiftExtractor& extractor) {
  Decoded d;
  try {
    Clock::time_point t0 = Clock::now();
    d.frame = source.Next();
    d.decode_seconds = Since(t0);
    if (d.frame) {
      t0 = Clock::now();
      d.features = extractor.Extract(d.frame->bgr);
      d.feature_seconds = Since(t0);
    }
  } catch (...) {
    d.error = std::current_exception();
  }
  return d;
}

// Decodes and extracts on its own thread into a bounded queue; stops and joins when destroyed
// (also when the consumer throws).
class Prefetcher {
 public:
  Prefetcher(FrameSource& source, const SiftExtractor& extractor, int capacity)
      : queue_(static_cast<size_t>(capacity)), thread_([this, &source, &extractor] {
          for (;;) {
            Decoded d = DecodeNext(source, extractor);
            const bool last = !d.frame || d.error;
            // Waits for room; false once the consumer has closed the queue (then d is dropped).
            if (!queue_.PushWait(std::move(d), kForever) || last) return;
          }
        }) {}
  ~Prefetcher() {
    queue_.Close();
    thread_.join();
  }
  Decoded Next() {
    std::optional<Decoded> d = queue_.Pop(kForever);  // the producer always ends with an item
    if (!d) throw std::logic_error("prefetch queue closed while the run was reading it");
    return std::move(*d);
  }

 private:
  static constexpr std::chrono::hours kForever{24 * 365};
  BoundedQueue<Decoded> queue_;
  std::thread thread_;
};

}  // namespace

void RunOptions::Check() const {
  if (threads < 0) throw std::invalid_argument("threads must be >= 0 (0 = automatic)");
  if (queue_frames < 1) throw std::invalid_argument("queue_frames must be >= 1");
}

int RunOptions::EffectiveThreads() const {
  if (threads > 0) return std::min(threads, 2);
  const unsigned hw = std::thread::hardware_concurrency();
  return hw >= 2 ? 2 : 1;
}

void ErrorHistogram::Add(double value) {
  const double bin = std::floor(std::max(value, 0.0) / kBin);
  ++counts[static_cast<size_t>(std::min(bin, kBins - 1.0))];
  ++n;
  max = std::max(max, value);
}

double ErrorHistogram::Quantile(double q) const {
  if (n == 0) return 0;
  const double target = std::clamp(q, 0.0, 1.0) * static_cast<double>(n);
  int64_t cumulative = 0;
  for (int b = 0; b < kBins; ++b) {
    cumulative += counts[b];
    if (cumulative > 0 && static_cast<double>(cumulative) >= target)
      return b == kBins - 1 ? max : std::min((b + 1) * kBin, max);
  }
  return max;
}

std::string RunSummary::Matching() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  const ErrorHistogram& h = prediction_error_px;
  s << "matching: " << fallbacks << " brute-force fallbacks in " << frames_with_fallback
    << " frames; prediction error of the inliers (px): p50 " << h.Quantile(0.5) << ", p90 "
    << h.Quantile(0.9) << ", p99 " << h.Quantile(0.99) << ", max " << h.max << " (" << h.n
    << " inliers)";
  return s.str();
}

std::string RunSummary::Brief() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << frames << " frames, " << accepted << " accepted, " << rejected << " rejected, mean inliers "
    << mean_inliers << ", " << (seconds > 0 ? frames / seconds : 0.0) << " fps";
  return s.str();
}

std::string RunSummary::Timing() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  const double ms = frames > 0 ? 1000.0 / frames : 0.0;
  s << "ms/frame: decode " << decode_seconds * ms << ", features " << stage_seconds.features * ms
    << ", matching " << stage_seconds.matching * ms << ", lifting " << stage_seconds.lifting * ms
    << ", ransac+refine " << stage_seconds.ransac * ms << ", writing " << write_seconds * ms
    << ", wall " << seconds * ms << " (" << threads << " thread" << (threads > 1 ? "s" : "") << ")";
  return s.str();
}

RunSummary RunOdometry(FrameSource& source, Odometry& odometry,
                       const std::vector<TrajectoryWriter*>& writers,
                       const std::function<void(const FrameResult&)>& on_frame,
                       const RunOptions& options) {
  options.Check();
  RunSummary summary;
  summary.threads = options.EffectiveThreads();
  const Clock::time_point start = Clock::now();
  double inlier_sum = 0;
  std::optional<Prefetcher> prefetcher;
  if (summary.threads > 1) prefetcher.emplace(source, odometry.extractor(), options.queue_frames);
  for (;;) {
    Decoded d = prefetcher ? prefetcher->Next() : DecodeNext(source, odometry.extractor());
    if (d.error) std::rethrow_exception(d.error);
    summary.decode_seconds += d.decode_seconds;
    if (!d.frame) break;
    FrameResult result = odometry.Process(*d.frame, std::move(d.features));
    result.times.features = d.feature_seconds;
    const Clock::time_point t0 = Clock::now();
    for (TrajectoryWriter* w : writers) w->Write(result);
    summary.write_seconds += Since(t0);

    ++summary.frames;
    if (result.status == FrameStatus::kFirst || result.status == FrameStatus::kAccepted)
      ++summary.accepted;
    else
      ++summary.rejected;
    if (result.status != FrameStatus::kFirst) inlier_sum += result.inliers;
    summary.stage_seconds.features += result.times.features;
    summary.stage_seconds.matching += result.times.matching;
    summary.stage_seconds.lifting += result.times.lifting;
    summary.stage_seconds.ransac += result.times.ransac;
    summary.fallbacks += result.fallbacks;
    if (result.fallbacks > 0) ++summary.frames_with_fallback;
    if (result.status == FrameStatus::kAccepted)
      for (float e : result.prediction_error_px) summary.prediction_error_px.Add(e);
    summary.seconds = Since(start);
    if (on_frame) on_frame(result);
  }
  summary.mean_inliers = summary.frames > 1 ? inlier_sum / (summary.frames - 1) : 0.0;
  summary.seconds = Since(start);
  return summary;
}

}  // namespace rgbdvo
