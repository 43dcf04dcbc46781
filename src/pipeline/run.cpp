#include "rgbdvo/pipeline/run.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <iomanip>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "rgbdvo/odometry/planarity_check.hpp"
#include "rgbdvo/odometry/tracking_gaps.hpp"
#include "rgbdvo/sensor/depth_check.hpp"
#include "rgbdvo/sensor/principal_point_check.hpp"
#include "rgbdvo/util/stopwatch.hpp"

namespace rgbdvo {
namespace {

// A frame with its features, or the end of the source, or the exception that stopped it (from
// the source or the feature extraction).
struct Decoded {
  std::optional<Frame> frame;
  std::optional<Features> features;  // none when the odometry extracts them itself
  double decode_seconds = 0, feature_seconds = 0;
  std::exception_ptr error;
};

// Reads the next frame into d (nothing at the end of the source); never throws: an error
// travels in d.error.
void ReadNext(FrameSource& source, Decoded* d) {
  try {
    const Stopwatch t0;
    d->frame = source.Next();
    d->decode_seconds = t0.Seconds();
  } catch (...) {
    d->error = std::current_exception();
  }
}

// Extracts the features of d's frame, if any and with an extractor; never throws.
void ExtractFeatures(const SiftExtractor* extractor, Decoded* d) {
  if (!d->frame || !extractor) return;
  try {
    const Stopwatch t0;
    d->features = extractor->Extract(d->frame->bgr);
    d->feature_seconds = t0.Seconds();
  } catch (...) {
    d->error = std::current_exception();
  }
}

Decoded DecodeNext(FrameSource& source, const SiftExtractor* extractor) {
  Decoded d;
  ReadNext(source, &d);
  ExtractFeatures(extractor, &d);
  return d;
}

// W feature workers feeding the calling thread in sequence order. Each worker takes the next
// frame from the source under `source_mutex_` (decoding is serial, so frames get consecutive
// sequence numbers in source order), extracts its features with the shared extractor
// (SiftExtractor::Extract is thread-safe) and files the result under its sequence
// number; Next() hands them out strictly in order. At most `capacity` frames are read ahead of
// the consumer. After the end of the source or an error no more frames are read; the
// destructor stops and joins the workers (also when the consumer throws).
class FeatureWorkers {
 public:
  // extractor: nullptr = decode only (the odometry runs SIFT where it needs it).
  FeatureWorkers(FrameSource& source, const SiftExtractor* extractor, int workers, int capacity)
      : source_(source), extractor_(extractor), capacity_(capacity) {
    try {
      for (int i = 0; i < workers; ++i) threads_.emplace_back([this] { Work(); });
    } catch (...) {  // no thread for the next worker: stop those started
      Stop();
      throw;
    }
  }
  ~FeatureWorkers() { Stop(); }
  FeatureWorkers(const FeatureWorkers&) = delete;
  FeatureWorkers& operator=(const FeatureWorkers&) = delete;

  // The next frame in sequence (or the end, or the error where the source failed); waits.
  // `waited` gets the seconds spent waiting.
  Decoded Next(double* waited) {
    const Stopwatch t0;
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [&] { return done_.count(consumed_) > 0; });
    *waited = t0.Seconds();
    auto it = done_.find(consumed_);
    Decoded d = std::move(it->second);
    done_.erase(it);
    ++consumed_;
    lock.unlock();
    room_.notify_all();
    return d;
  }

 private:
  void Stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    room_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  void Work() {
    for (;;) {
      std::unique_lock<std::mutex> source_lock(source_mutex_);
      int64_t seq;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        room_.wait(lock, [&] { return stop_ || ended_ || read_ - consumed_ < capacity_; });
        if (stop_ || ended_) return;
        seq = read_++;
      }
      Decoded d;
      ReadNext(source_, &d);
      if (!d.frame) {  // the end or an error: nothing after it is read
        std::lock_guard<std::mutex> lock(mutex_);
        ended_ = true;
      }
      source_lock.unlock();
      ExtractFeatures(extractor_, &d);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        done_.emplace(seq, std::move(d));
      }
      ready_.notify_one();  // only the calling thread waits on ready_
    }
  }

  FrameSource& source_;
  const SiftExtractor* extractor_;
  const int64_t capacity_;
  std::mutex source_mutex_;  // serialises source_.Next()
  std::mutex mutex_;         // guards everything below
  std::condition_variable ready_, room_;
  std::map<int64_t, Decoded> done_;  // reorder buffer: finished frames by sequence number
  int64_t read_ = 0;                 // frames taken from the source
  int64_t consumed_ = 0;             // frames handed to the calling thread
  bool ended_ = false;               // the source ended or failed
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace

void RunOptions::Check() const {
  if (threads < 0) throw std::invalid_argument("run.threads must be >= 0 (0 = automatic)");
  if (queue_frames < 1) throw std::invalid_argument("run.queue_frames must be >= 1");
}

int RunOptions::EffectiveThreads() const {
  if (threads > 0) return threads;
  const int hw = static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(hw, 1, kMaxAutoThreads);
}

int RunOptions::EffectiveQueueFrames() const {
  const int workers = EffectiveThreads();
  return workers > 1 ? std::max(queue_frames, workers) : 0;
}

std::string RunOptions::Describe() const {
  const int n = EffectiveThreads();
  if (n == 1) return "1 thread";
  return std::to_string(n) + " feature workers + the main thread, at most " +
         std::to_string(EffectiveQueueFrames()) + " frames read ahead" +
         (parallel_keyframe_sift ? ", a new keyframe's two SIFT runs side by side" : "");
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
    << " frames, " << rematches
    << " matched again around the estimate; prediction error of the inliers (px): p50 "
    << h.Quantile(0.5) << ", p90 " << h.Quantile(0.9) << ", p99 " << h.Quantile(0.99) << ", max "
    << h.max << " (" << h.n << " inliers)";
  if (frames_from_tracks > 0 || sift_runs > 0)
    s << "; tracking: " << frames_from_tracks << " of " << frames
      << " frames from tracks, SIFT run " << sift_runs << " times";
  return s.str();
}

std::string RunSummary::Brief() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << frames << " frames, " << accepted << " accepted, " << recovered << " recovered, " << depth
    << " icp, " << predicted << " predicted, " << rejected << " rejected, " << lost
    << " lost, longest gap " << longest_gap_frames << " frames (" << std::setprecision(2)
    << longest_gap_seconds << " s), mean inliers " << std::setprecision(1) << mean_inliers << ", "
    << (seconds > 0 ? frames / seconds : 0.0) << " fps";
  if (rows_left_out > 0)
    s << "; " << rows_left_out
      << " frames left out of the TUM/KITTI files (their depth image's time repeats an earlier "
         "row's)";
  return s.str();
}

std::string RunSummary::Timing() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  const double ms = frames > 0 ? 1000.0 / frames : 0.0;
  s << "ms/frame: decode " << decode_seconds * ms << ", features " << stage_seconds.features * ms
    << ", matching " << stage_seconds.matching * ms << ", lifting " << stage_seconds.lifting * ms
    << ", ransac+refine " << stage_seconds.ransac * ms << ", map " << stage_seconds.local_map * ms
    << ", writing " << write_seconds * ms << ", waiting " << wait_seconds * ms << ", wall "
    << seconds * ms << " ("
    << (threads > 1 ? std::to_string(threads) + " feature workers" : "1 thread") << ")";
  return s.str();
}

RunSummary RunOdometry(FrameSource& source, Odometry& odometry,
                       const std::vector<TrajectoryWriter*>& writers,
                       const std::function<void(const FrameResult&)>& on_frame,
                       const RunOptions& options,
                       const std::function<void(const std::string&)>& on_warning) {
  options.Check();
  RunSummary summary;
  summary.threads = options.EffectiveThreads();
  odometry.SetThreads(options.parallel_keyframe_sift ? summary.threads : 1);
  const Stopwatch start;
  double inlier_sum = 0;
  TrackingGaps gaps;
  std::optional<PlanarityCheck> planarity;  // with the planar motion model
  std::optional<FeatureWorkers> workers;
  const SiftExtractor* extractor = odometry.ExtractsLazily() ? nullptr : &odometry.extractor();
  if (summary.threads > 1)
    workers.emplace(source, extractor, summary.threads, options.EffectiveQueueFrames());
  for (;;) {
    double waited = 0;
    Decoded d = workers ? workers->Next(&waited) : DecodeNext(source, extractor);
    summary.wait_seconds += waited;
    if (d.error) std::rethrow_exception(d.error);
    summary.decode_seconds += d.decode_seconds;
    if (!d.frame) break;
    if (summary.frames == 0 && on_warning) {
      const Calibration& calib = odometry.calibration();
      const cv::Mat& depth = d.frame->depth_m;
      for (const std::optional<std::string>& w :
           {CheckDepthScale(depth, calib), CheckPrincipalPoint(calib, depth.cols, depth.rows)})
        if (w) on_warning("frame " + std::to_string(d.frame->index) + ": " + *w);
    }
    FrameResult result;
    if (d.features) {
      result = odometry.Process(std::move(*d.frame), std::move(*d.features));
      result.times.features = d.feature_seconds;
    } else {
      result = odometry.Process(std::move(*d.frame));  // SIFT where needed, timed by it
    }
    const Stopwatch t0;
    for (TrajectoryWriter* w : writers) w->Write(result);
    summary.write_seconds += t0.Seconds();

    ++summary.frames;
    switch (result.status) {
      case FrameStatus::kFirst:
      case FrameStatus::kAccepted:
        ++summary.accepted;
        break;
      case FrameStatus::kRecovered:
        ++summary.recovered;
        break;
      case FrameStatus::kDepth:
        ++summary.depth;
        break;
      case FrameStatus::kPredicted:
        ++summary.predicted;
        break;
      case FrameStatus::kRejected:
        ++summary.rejected;
        break;
      case FrameStatus::kLost:
        ++summary.lost;
        break;
    }
    if (std::optional<std::string> warning = gaps.Add(result); warning && on_warning)
      on_warning(*warning);
    if (!planarity && odometry.level_from_cam())  // the floor's normal in the first camera
      planarity.emplace(PlanarityCheckOptions{}, odometry.level_from_cam()->row(1).transpose());
    if (planarity)
      if (std::optional<std::string> warning = planarity->Add(result); warning && on_warning)
        on_warning(*warning);
    if (result.status != FrameStatus::kFirst) inlier_sum += result.inliers;
    summary.stage_seconds.features += result.times.features;
    summary.stage_seconds.matching += result.times.matching;
    summary.stage_seconds.lifting += result.times.lifting;
    summary.stage_seconds.ransac += result.times.ransac;
    summary.stage_seconds.local_map += result.times.local_map;
    summary.fallbacks += result.fallbacks;
    if (result.fallbacks > 0) ++summary.frames_with_fallback;
    summary.rematches += result.rematches;
    if (result.from_tracks) ++summary.frames_from_tracks;
    summary.sift_runs += result.sift_runs;
    if (result.status == FrameStatus::kAccepted)
      for (float e : result.prediction_error_px) summary.prediction_error_px.Add(e);
    summary.seconds = start.Seconds();
    if (on_frame) on_frame(result);
  }
  if (std::optional<std::string> warning = gaps.Finish(); warning && on_warning)
    on_warning(*warning);
  if (planarity) {
    summary.non_planar_frames = planarity->off_plane_frames();
    summary.non_planar_episodes = planarity->episodes();
  }
  summary.longest_gap_frames = gaps.longest_frames();
  summary.longest_gap_seconds = gaps.longest_seconds();
  for (const TrajectoryWriter* w : writers)
    summary.rows_left_out = std::max(summary.rows_left_out, w->rows_left_out());
  summary.mean_inliers = summary.frames > 1 ? inlier_sum / (summary.frames - 1) : 0.0;
  summary.seconds = start.Seconds();
  return summary;
}

}  // namespace rgbdvo
