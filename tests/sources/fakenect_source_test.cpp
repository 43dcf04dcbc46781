#include "rgbdvo/sources/fakenect_source.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>

#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"
#include "rgbdvo/sources/fakenect_files.hpp"
#include "rgbdvo/sources/open_source.hpp"
#include "rgbdvo/synthetic/synthetic_kinect.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

namespace {

// A small (160x120) synthetic Kinect recording of n frames.
SyntheticKinectOptions Small() {
  SyntheticKinectOptions o;
  o.color = {131.25, 131.25, 79.5, 59.5, 160, 120};
  o.ir = {145.0, 145.0, 80.0, 60.0, 160, 120};
  return o;
}

std::string SmallRecording(const std::string& tag, int n) {
  std::string dir = MakeTempDir(tag) + "/rec";
  WriteSyntheticKinectRecording(dir, SyntheticScene(), Small(), MakeKinectRangePath(n));
  return dir;
}

std::vector<std::string> IndexLines(const std::string& dir) {
  return ReadFakenectIndex(dir + "/INDEX.txt");
}

}  // namespace

TEST_CASE("FakenectSource pairs each colour frame with its depth frame, in metres") {
  const std::string dir = SmallRecording("fsrc", 3);
  REQUIRE(IsFakenectFolder(dir));
  FakenectSource source(dir, {});
  CHECK(source.size() == 3);
  CHECK(source.unpaired() == 0);
  CHECK_THAT(source.Describe(),
             Catch::Contains("3 colour-depth pairs") && Catch::Contains("3 accelerometer entries"));
  const SyntheticKinectOptions o = Small();
  const std::vector<Rigid3d> path = MakeKinectRangePath(3);
  Rigid3d color_from_ir = Rigid3d::Identity();
  color_from_ir.translation() = o.ir_in_color;
  for (int k = 0; k < 3; ++k) {
    const std::optional<Frame> f = source.Next();
    REQUIRE(f);
    CHECK(f->index == k);
    // Stamped by the device's clock (60 MHz ticks; the depth frame 1000 ticks after the colour
    // frame) from the first entry's host time.
    CHECK(f->color_timestamp == Approx((o.start_us + k * o.period_us) * 1e-6).margin(1e-6));
    CHECK(f->timestamp - f->color_timestamp == Approx(1000 / 60.0 * 1e-6).margin(1e-6));
    CHECK(f->bgr.size() == cv::Size(160, 120));
    // The depth is the IR camera's Z, to within the raw quantisation (< 2 cm within 2.5 m).
    const cv::Mat truth = SyntheticScene().RenderDepth(o.ir, path[k] * color_from_ir);
    const cv::Mat close = truth < 2.5;
    CHECK(cv::norm(truth, f->depth_m, cv::NORM_INF, close) < 0.01);
  }
  CHECK(!source.Next());
}

TEST_CASE("FakenectSource gives each frame the accelerometer's gravity in the camera frame") {
  const std::string dir = SmallRecording("fsrc_accel", 3);
  FakenectSourceOptions options;
  options.accelerometer = true;
  FakenectSource source(dir, options);
  const std::vector<Rigid3d> path = MakeKinectRangePath(3);
  for (int k = 0; k < 3; ++k) {
    const std::optional<Frame> f = source.Next();
    REQUIRE(f);
    REQUIRE(f->gravity_in_cam);
    // The synthetic world's down is +y; written in the Kinect's axes and counts, read back.
    const Eigen::Vector3d truth =
        path[k].linear().transpose() * Eigen::Vector3d(0, kStandardGravity, 0);
    INFO("frame " << k << ": " << f->gravity_in_cam->transpose() << " against "
                  << truth.transpose());
    CHECK((*f->gravity_in_cam - truth).norm() < 0.02);  // 1.5 counts of 0.012 m/s^2
  }
  FakenectSource without(dir, {});
  CHECK_FALSE(without.Next()->gravity_in_cam);
}

TEST_CASE("FakenectSource: accelerometer readings asked for but absent or broken are errors") {
  const std::string dir = SmallRecording("fsrc_accel_bad", 2);
  const std::vector<std::string> names = IndexLines(dir);  // r a d r a d
  FakenectSourceOptions options;
  options.accelerometer = true;
  SECTION("a truncated entry is named") {
    fs::resize_file(dir + "/" + names[4], 3);
    CHECK_THROWS_WITH(FakenectSource(dir, options), Catch::Contains(names[4]));
  }
  SECTION("a recording without entries says so") {
    std::ofstream index(dir + "/INDEX.txt", std::ios::trunc);
    for (const std::string& n : names)
      if (n[0] != 'a') index << n << "\n";
    index.close();
    CHECK_THROWS_WITH(FakenectSource(dir, options), Catch::Contains("no accelerometer entries"));
    CHECK_NOTHROW(FakenectSource(dir, {}));
  }
}

TEST_CASE("FakenectSource reads an INDEX.txt with CRLF line ends and blank lines") {
  const std::string dir = SmallRecording("fsrc_crlf", 2);
  const std::vector<std::string> names = IndexLines(dir);
  {
    std::ofstream out(dir + "/INDEX.txt", std::ios::binary | std::ios::trunc);
    out << "\r\n";
    for (const std::string& n : names) out << n << "\r\n\r\n";
  }
  FakenectSource source(dir, {});
  CHECK(source.size() == 2);
  CHECK(source.Next());
  CHECK(source.Next());
  CHECK(!source.Next());
}

TEST_CASE("FakenectSource: missing and truncated files are errors naming the file") {
  const std::string dir = SmallRecording("fsrc_bad", 3);
  const std::vector<std::string> names = IndexLines(dir);  // r a d r a d r a d
  REQUIRE(names.size() == 9);

  SECTION("a truncated depth image stops at that frame") {
    fs::resize_file(dir + "/" + names[5], 1000);
    FakenectSource source(dir, {});
    CHECK(source.Next());
    CHECK_THROWS_WITH(source.Next(), Catch::Contains(names[5]) && Catch::Contains("truncated"));
  }
  SECTION("a missing file is reported before anything runs") {
    fs::remove(dir + "/" + names[3]);
    fs::remove(dir + "/" + names[8]);
    CHECK_THROWS_WITH(FakenectSource(dir, {}), Catch::Contains(names[3]) &&
                                                   Catch::Contains("missing") &&
                                                   Catch::Contains("2 missing"));
  }
  SECTION("a line that is not a fakenect name is reported with its position") {
    std::ofstream(dir + "/INDEX.txt", std::ios::app) << "rgb/000001.png\n";
    CHECK_THROWS_WITH(FakenectSource(dir, {}), Catch::Contains("INDEX.txt") &&
                                                   Catch::Contains("entry 10") &&
                                                   Catch::Contains("rgb/000001.png"));
  }
  SECTION("an index without any pair is an empty sequence") {
    std::ofstream(dir + "/INDEX.txt", std::ios::trunc) << names[0] << "\n" << names[1] << "\n";
    CHECK_THROWS_WITH(FakenectSource(dir, {}), Catch::Contains("empty sequence"));
  }
}

TEST_CASE("OpenRecording detects the fakenect layout, with or without INDEX.txt") {
  const std::string dir = SmallRecording("fsrc_open", 2);
  std::unique_ptr<FrameSource> source = OpenRecording(dir, {});
  CHECK(dynamic_cast<FakenectSource*>(source.get()) != nullptr);
  // Without INDEX.txt (as in some copies of NYU Depth V2 raw scenes) the frame files are
  // taken in wall-clock order.
  fs::remove(dir + "/INDEX.txt");
  FakenectSource listed(dir, {});
  CHECK(listed.size() == 2);
  CHECK_THAT(listed.Describe(), Catch::Contains("no INDEX.txt"));
  CHECK(listed.Next()->color_timestamp == Approx(Small().start_us * 1e-6).margin(1e-6));
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() != ".yaml") fs::remove(e.path());
  CHECK_THROWS_WITH(OpenRecording(dir, {}),
                    Catch::Contains("unknown recording layout") && Catch::Contains("INDEX.txt"));
}

TEST_CASE("A fakenect recording is stamped by the device clock, not by jittered arrival times") {
  // On a busy host the arrival times in the file names lag by tens of milliseconds, differently
  // for each frame; the stamps (and so the depth delay and the motion prior) must not follow.
  const std::string dir = SmallRecording("fjitter", 5);
  const std::string jittered = MakeTempDir("fjitter2");
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> jitter_us(0, 40000);
  std::ofstream index(jittered + "/INDEX.txt");
  const std::vector<std::string> lines = IndexLines(dir);
  for (size_t i = 0; i < lines.size(); ++i) {
    FakenectName n = *ParseFakenectName(lines[i]);
    if (i > 0) n.wallclock_us += jitter_us(rng);  // the first entry anchors the clock
    fs::copy_file(fs::path(dir) / lines[i], fs::path(jittered) / n.ToString());
    index << n.ToString() << "\n";
  }
  index.close();
  FakenectSource original(dir, {}), shaken(jittered, {});
  REQUIRE(shaken.size() == original.size());
  for (size_t k = 0; k < original.size(); ++k) {
    const std::optional<Frame> a = original.Next(), b = shaken.Next();
    REQUIRE((a && b));
    CHECK(b->color_timestamp == Approx(a->color_timestamp).margin(1e-6));
    CHECK(b->timestamp == Approx(a->timestamp).margin(1e-6));
  }
}

TEST_CASE("A fakenect recording paired one to one uses each depth frame once") {
  // Without the second depth frame, colour frame 1 is 33.3 ms from depth frames 0 and 2, within
  // the 34 ms window: nearest pairing gives it one of them, shared with a neighbour; one to one
  // leaves it without a depth frame of its own.
  const std::string dir = SmallRecording("fone", 4);
  std::vector<std::string> lines = IndexLines(dir);
  const auto second_depth =
      std::find_if(lines.begin(), lines.end(),
                   [n = 0](const std::string& l) mutable { return l[0] == 'd' && n++ == 1; });
  REQUIRE(second_depth != lines.end());
  lines.erase(second_depth);
  std::ofstream index(dir + "/INDEX.txt");
  for (const std::string& l : lines) index << l << "\n";
  index.close();
  FakenectSourceOptions options;
  FakenectSource nearest(dir, options);
  CHECK(nearest.size() == 4);
  options.pairing = Pairing::kOneToOne;
  FakenectSource one(dir, options);
  CHECK(one.size() == 3);
  CHECK(one.unpaired() == 1);
  std::vector<double> depth_times;
  while (const std::optional<Frame> f = one.Next()) depth_times.push_back(f->timestamp);
  REQUIRE(depth_times.size() == 3);
  CHECK(depth_times[0] < depth_times[1]);
  CHECK(depth_times[1] < depth_times[2]);
}
