#include "rgbdvo/run.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <stdexcept>

#include "rgbdvo/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// Renders a smooth synthetic path; throws at frame `throw_at` (-1 = never).
class SyntheticSource : public FrameSource {
 public:
  SyntheticSource(int n, int throw_at) : path_(MakeSmoothPath(n, 0.01, 0.8)), throw_at_(throw_at) {}
  std::optional<Frame> Next() override {
    if (next_ == throw_at_)
      throw std::runtime_error("frame " + std::to_string(next_) + ": unreadable");
    if (next_ >= static_cast<int>(path_.size())) return std::nullopt;
    Frame f;
    f.index = next_;
    f.timestamp = f.color_timestamp = next_ / 30.0;
    f.bgr = scene_.RenderColor(cam_, path_[next_]);
    f.depth_m = scene_.RenderDepth(cam_, path_[next_]);
    ++next_;
    return f;
  }
  std::string Describe() const override { return "synthetic"; }
  Calibration Calib() const {
    Calibration c;
    c.fx = cam_.fx;
    c.fy = cam_.fy;
    c.cx = cam_.cx;
    c.cy = cam_.cy;
    return c;
  }

 private:
  SyntheticScene scene_;
  PinholeCamera cam_;
  std::vector<Rigid3d> path_;
  int throw_at_;
  int next_ = 0;
};

class Recorder : public TrajectoryWriter {
 public:
  void Write(const FrameResult& r) override { rows.push_back(r); }
  std::vector<FrameResult> rows;
};

std::vector<FrameResult> RunWith(int threads, int n, int throw_at, std::string* error) {
  SyntheticSource source(n, throw_at);
  Odometry odometry(OdometryOptions{}, source.Calib());
  Recorder recorder;
  RunOptions options;
  options.threads = threads;
  try {
    const RunSummary s = RunOdometry(source, odometry, {&recorder}, {}, options);
    CHECK(s.threads == threads);
    CHECK(s.frames == static_cast<int>(recorder.rows.size()));
  } catch (const std::runtime_error& e) {
    *error = e.what();
  }
  return recorder.rows;
}

}  // namespace

TEST_CASE("The two-thread pipeline gives the same results in the same order as one thread") {
  std::string error;
  const std::vector<FrameResult> one = RunWith(1, 8, -1, &error);
  const std::vector<FrameResult> two = RunWith(2, 8, -1, &error);
  CHECK(error.empty());
  REQUIRE(one.size() == 8);
  REQUIRE(two.size() == one.size());
  for (size_t i = 0; i < one.size(); ++i) {
    CHECK(two[i].frame == static_cast<int>(i));
    CHECK(two[i].status == one[i].status);
    CHECK(two[i].inliers == one[i].inliers);
    CHECK(two[i].world_from_cam.matrix() == one[i].world_from_cam.matrix());
  }
}

TEST_CASE("A source error stops the pipeline after writing every frame before it") {
  for (int threads : {1, 2}) {
    std::string error;
    const std::vector<FrameResult> rows = RunWith(threads, 8, 3, &error);
    INFO("threads " << threads);
    CHECK(error == "frame 3: unreadable");
    REQUIRE(rows.size() == 3);
    CHECK(rows.back().frame == 2);
  }
}

TEST_CASE("A writer error stops the pipeline and propagates") {
  class Failing : public TrajectoryWriter {
   public:
    void Write(const FrameResult& r) override {
      if (r.frame == 2) throw std::runtime_error("disk full");
    }
  } failing;
  SyntheticSource source(8, -1);
  Odometry odometry(OdometryOptions{}, source.Calib());
  RunOptions options;
  options.threads = 2;
  CHECK_THROWS_WITH(RunOdometry(source, odometry, {&failing}, {}, options), "disk full");
}

TEST_CASE("RunOptions::Check names the field") {
  RunOptions o;
  o.threads = -1;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("threads"));
  o = RunOptions{};
  o.queue_frames = 0;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("queue_frames"));
  CHECK(RunOptions{}.EffectiveThreads() >= 1);
}

TEST_CASE("ErrorHistogram quantiles are within one bin of the exact ones") {
  ErrorHistogram h;
  CHECK(h.Quantile(0.5) == 0);
  std::vector<double> values;
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
