#include "rgbdvo/pipeline/run.hpp"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>

#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// Renders a smooth synthetic path; throws at frame `throw_at` (-1 = never); gives frame
// `empty_at` an empty colour image (feature extraction then fails; -1 = never).
class SyntheticSource : public FrameSource {
 public:
  SyntheticSource(int n, int throw_at, int empty_at = -1)
      : path_(MakeSmoothPath(n, 0.01, 0.8)), throw_at_(throw_at), empty_at_(empty_at) {}
  std::optional<Frame> Next() override {
    ++calls_;
    if (next_ == throw_at_)
      throw std::runtime_error("frame " + std::to_string(next_) + ": unreadable");
    if (next_ >= static_cast<int>(path_.size())) return std::nullopt;
    Frame f;
    f.index = next_;
    f.timestamp = f.color_timestamp = next_ / 30.0;
    if (next_ != empty_at_) f.bgr = scene_.RenderColor(cam_, path_[next_]);
    f.depth_m = scene_.RenderDepth(cam_, path_[next_]);
    ++next_;
    return f;
  }
  int calls() const { return calls_; }  // Next() calls so far (any thread may ask)
  std::string Describe() const override { return "synthetic"; }
  Calibration Calib() const { return CalibFor(cam_); }

 private:
  SyntheticScene scene_;
  PinholeCamera cam_;
  std::vector<Rigid3d> path_;
  int throw_at_, empty_at_;
  int next_ = 0;
  std::atomic<int> calls_{0};
};

class Recorder : public TrajectoryWriter {
 public:
  void Write(const FrameResult& r) override { rows.push_back(r); }
  std::vector<FrameResult> rows;
};

std::vector<FrameResult> RunWith(int threads, int n, int throw_at, std::string* error,
                                 int empty_at = -1, int queue_frames = RunOptions{}.queue_frames,
                                 const OdometryOptions& odometry_options = {},
                                 RunSummary* summary = nullptr,
                                 bool parallel_keyframe_sift = false) {
  SyntheticSource source(n, throw_at, empty_at);
  Odometry odometry(odometry_options, source.Calib());
  Recorder recorder;
  RunOptions options;
  options.threads = threads;
  options.queue_frames = queue_frames;
  options.parallel_keyframe_sift = parallel_keyframe_sift;
  try {
    const RunSummary s = RunOdometry(source, odometry, {&recorder}, {}, options);
    CHECK(s.threads == threads);
    CHECK(s.frames == static_cast<int>(recorder.rows.size()));
    if (summary) *summary = s;
  } catch (const std::exception& e) {
    *error = e.what();
  }
  return recorder.rows;
}

}  // namespace

TEST_CASE("Feature workers give the same results in the same order as one thread") {
  OdometryOptions sift_every_frame;
  sift_every_frame.track_between_keyframes = false;
  std::string error;
  RunSummary summary;
  const std::vector<FrameResult> one = RunWith(1, 8, -1, &error, -1, 4, sift_every_frame, &summary);
  REQUIRE(one.size() == 8);
  // Features come with the frames: nothing tracked, no SIFT run by the odometry.
  CHECK(summary.frames_from_tracks == 0);
  CHECK(summary.sift_runs == 0);
  CHECK_THAT(summary.Matching(), !Catch::Contains("tracking:"));
  for (int threads : {2, 3}) {
    for (int queue_frames : {1, 4}) {  // 1 is raised to the number of workers
      INFO("threads " << threads << ", queue_frames " << queue_frames);
      const std::vector<FrameResult> many =
          RunWith(threads, 8, -1, &error, -1, queue_frames, sift_every_frame);
      CHECK(error.empty());
      REQUIRE(many.size() == one.size());
      for (size_t i = 0; i < one.size(); ++i) {
        CHECK(many[i].frame == static_cast<int>(i));
        CHECK(many[i].status == one[i].status);
        CHECK(many[i].features == one[i].features);
        CHECK(many[i].inliers == one[i].inliers);
        CHECK(many[i].world_from_cam.matrix() == one[i].world_from_cam.matrix());
      }
    }
  }
}

TEST_CASE(
    "With tracking between keyframes the workers only decode, and the results are one thread's") {
  OdometryOptions tracking;
  tracking.track_between_keyframes = true;
  // Keyframes renewed as soon as the tracked inliers fall: a new keyframe and the frame before
  // it then both need SIFT, which two threads run one after the other or side by side.
  tracking.keyframe_inlier_ratio = 0.98;
  std::string error;
  RunSummary summary;
  const std::vector<FrameResult> one = RunWith(1, 10, -1, &error, -1, 4, tracking, &summary);
  REQUIRE(one.size() == 10);
  for (const bool parallel : {false, true}) {
    INFO("a keyframe's SIFT runs side by side: " << parallel);
    const std::vector<FrameResult> two =
        RunWith(2, 10, -1, &error, -1, 4, tracking, nullptr, parallel);
    CHECK(error.empty());
    REQUIRE(two.size() == one.size());
    for (size_t i = 0; i < one.size(); ++i) {
      INFO("frame " << i);
      CHECK(two[i].status == one[i].status);
      CHECK(two[i].features == one[i].features);
      CHECK(two[i].inliers == one[i].inliers);
      CHECK(two[i].world_from_cam.matrix() == one[i].world_from_cam.matrix());
      // SIFT's time is the odometry's own, counted only where it ran.
      CHECK((one[i].times.features == 0) == (two[i].times.features == 0));
      CHECK(two[i].sift_runs == one[i].sift_runs);
    }
  }
  int without_sift = 0, fused = 0;
  for (const FrameResult& r : one) {
    if (r.times.features == 0) ++without_sift;
    // A new keyframe and the frame before it, SIFT on both.
    if (r.sift_runs == 2) ++fused;
  }
  CHECK(without_sift > 0);
  CHECK(fused > 0);
  // The summary counts what the odometry reported.
  int from_tracks = 0, sift_runs = 0;
  for (const FrameResult& r : one) {
    from_tracks += r.from_tracks ? 1 : 0;
    sift_runs += r.sift_runs;
  }
  CHECK(from_tracks > 0);
  CHECK(summary.frames_from_tracks == from_tracks);
  CHECK(summary.sift_runs == sift_runs);
  CHECK_THAT(summary.Matching(), Catch::Contains("tracking: " + std::to_string(from_tracks) +
                                                 " of 10 frames from tracks, SIFT run " +
                                                 std::to_string(sift_runs) + " times"));
  for (int threads : {1, 3}) {  // an empty colour image fails where the odometry reads it
    INFO("threads " << threads);
    std::string failed;
    const std::vector<FrameResult> rows = RunWith(threads, 8, -1, &failed, 4, 4, tracking);
    CHECK_THAT(failed, Catch::Contains("empty image"));
    CHECK(rows.size() == 4);
  }
}

TEST_CASE("A source error stops the pipeline after writing every frame before it") {
  for (int threads : {1, 2, 3}) {
    std::string error;
    const std::vector<FrameResult> rows = RunWith(threads, 8, 3, &error);
    INFO("threads " << threads);
    CHECK(error == "frame 3: unreadable");
    REQUIRE(rows.size() == 3);
    CHECK(rows.back().frame == 2);
  }
}

TEST_CASE("A feature extraction error stops the pipeline after writing every frame before it") {
  for (int threads : {1, 3}) {
    std::string error;
    const std::vector<FrameResult> rows = RunWith(threads, 8, -1, &error, 4);
    INFO("threads " << threads);
    CHECK_THAT(error, Catch::Contains("empty image"));
    REQUIRE(rows.size() == 4);
    CHECK(rows.back().frame == 3);
  }
}

TEST_CASE("Workers read at most queue_frames frames ahead of the odometry") {
  SyntheticSource source(12, -1);
  Odometry odometry(OdometryOptions{}, source.Calib());
  RunOptions options;
  options.threads = 2;
  options.queue_frames = 3;
  int max_ahead = 0;
  // When frame k is done, frames 0..k have been handed over, so at most k + 1 + 3 were read.
  RunOdometry(
      source, odometry, {},
      [&](const FrameResult& r) {
        max_ahead = std::max(max_ahead, source.calls() - (r.frame + 1));
      },
      options);
  CHECK(max_ahead <= 3);
  CHECK(source.calls() == 13);  // 12 frames and the end
}

TEST_CASE("A writer error stops the pipeline and propagates") {
  class Failing : public TrajectoryWriter {
   public:
    void Write(const FrameResult& r) override {
      if (r.frame == 2) throw std::runtime_error("disk full");
    }
  } failing;
  for (int threads : {1, 2, 3}) {
    INFO("threads " << threads);
    SyntheticSource source(8, -1);
    Odometry odometry(OdometryOptions{}, source.Calib());
    RunOptions options;
    options.threads = threads;
    CHECK_THROWS_WITH(RunOdometry(source, odometry, {&failing}, {}, options), "disk full");
  }
}

TEST_CASE("The run ends cleanly when the odometry fails while every worker waits for room") {
  // Frames 0-2 handed over and queue_frames 3: the workers read frames up to 5 and then wait
  // for room; the writer waits for that (or gives up after 20 s) and throws. The workers must
  // be woken and joined: RunOdometry returns with the writer's exception instead of hanging.
  SyntheticSource source(12, -1);
  class Failing : public TrajectoryWriter {
   public:
    explicit Failing(const SyntheticSource& s) : source(s) {}
    void Write(const FrameResult& r) override {
      if (r.frame < 2) return;
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (source.calls() < 6 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      reached = source.calls();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));  // workers now wait for room
      throw std::runtime_error("disk full");
    }
    const SyntheticSource& source;
    int reached = 0;
  } failing(source);
  Odometry odometry(OdometryOptions{}, source.Calib());
  RunOptions options;
  options.threads = 3;
  options.queue_frames = 3;
  CHECK_THROWS_WITH(RunOdometry(source, odometry, {&failing}, {}, options), "disk full");
  CHECK(failing.reached == 6);
  CHECK(source.calls() == 6);  // nothing read after the window was full
}

TEST_CASE("RunOptions::Check names the field") {
  RunOptions o;
  o.threads = -1;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("threads"));
  o = RunOptions{};
  o.queue_frames = 0;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("queue_frames"));
  CHECK(RunOptions{}.EffectiveThreads() >= 1);
  CHECK(RunOptions{}.EffectiveThreads() <= RunOptions::kMaxAutoThreads);
  o = RunOptions{};
  o.threads = 3;
  o.queue_frames = 1;
  CHECK(o.EffectiveThreads() == 3);
  CHECK(o.EffectiveQueueFrames() == 3);  // raised to the number of workers
  CHECK(o.Describe() == "3 feature workers + the main thread, at most 3 frames read ahead");
  o.parallel_keyframe_sift = true;
  CHECK(o.Describe() ==
        "3 feature workers + the main thread, at most 3 frames read ahead, a "
        "new keyframe's two SIFT runs side by side");
  o.threads = 1;
  CHECK(o.EffectiveQueueFrames() == 0);
  CHECK(o.Describe() == "1 thread");
}

TEST_CASE("ErrorHistogram quantiles are within one bin of the exact ones") {
  ErrorHistogram h;
  CHECK(h.Quantile(0.5) == 0);
  std::vector<double> values;
  values.reserve(5001);
  std::mt19937 rng(11);
  std::exponential_distribution<double> e(0.3);  // mean 3.3 px, a tail beyond 100 px is rare
  for (int k = 0; k < 5000; ++k) values.push_back(e(rng));
  values.push_back(250.0);  // beyond the last bin
  for (double v : values) h.Add(v);
  std::sort(values.begin(), values.end());
  CHECK(h.n == static_cast<int64_t>(values.size()));
  CHECK(h.max == 250.0);
  for (double q : {0.5, 0.9, 0.99}) {
    const double exact = values[static_cast<size_t>(std::ceil(q * values.size())) - 1];
    INFO("q " << q << " exact " << exact << " histogram " << h.Quantile(q));
    CHECK(h.Quantile(q) >= exact);
    CHECK(h.Quantile(q) <= exact + ErrorHistogram::kBin + 1e-9);
  }
  CHECK(h.Quantile(1.0) == 250.0);
}
