// End-to-end tests of `rgbdvo capture`, really run through libfreenect's API: Debian's
// `fakenect` replays a synthetic Kinect recording in place of the device.
#include <libfreenect.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>

#include "rgbdvo/sources/fakenect_files.hpp"
#include "rgbdvo/sources/fakenect_source.hpp"
#include "rgbdvo/synthetic/synthetic_kinect.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

namespace {

constexpr int kFrames = 20;

// Poses of a TUM trajectory file.
std::vector<Rigid3d> ReadTumPoses(const std::string& path) {
  std::vector<Rigid3d> poses;
  for (const std::string& line : Lines(path)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double t, x, y, z, qx, qy, qz, qw;
    s >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
    poses.push_back(MakeRigid(Eigen::Quaterniond(qw, qx, qy, qz), {x, y, z}));
  }
  return poses;
}

// The synthetic 640x480 Kinect recording shared by the tests (made once per test process),
// and the IR camera's true path.
const std::string& Recording(std::vector<Rigid3d>* truth = nullptr) {
  static std::vector<Rigid3d> ir_poses;
  static const std::string dir = [] {
    std::string d = MakeTempDir("kinect") + "/rec";
    ir_poses = WriteSyntheticKinectRecording(d, SyntheticScene(), SyntheticKinectOptions(),
                                             MakeKinectRangePath(kFrames));
    return d;
  }();
  if (truth) *truth = ir_poses;
  return dir;
}

// `rgbdvo capture` replaying `rec` through fakenect (calibration: the synthetic one).
int Capture(const std::string& rec, const std::string& args, std::string* out) {
  // The test build where the arguments use its flags (apps/debug_flags.hpp).
  const std::string exe =
      args.find("--debug-") != std::string::npos ? RgbdvoDebugExe() : RgbdvoExe();
  return RunCommand(
      "fakenect " + rec + " " + exe + " capture --calib " + Recording() + "/calib.yaml " + args,
      out);
}

// The r-/d-/a- entries of a recording: type, device timestamp and the file's bytes.
struct Entry {
  char type;
  uint32_t device_ts;
  std::string bytes;
};
std::vector<Entry> Entries(const std::string& dir) {
  std::vector<Entry> entries;
  for (const std::string& name : ReadFakenectIndex(dir + "/INDEX.txt")) {
    const auto n = ParseFakenectName(name);
    REQUIRE(n);
    entries.push_back({n->type, n->device_ts, Slurp(dir + "/" + name)});
  }
  return entries;
}
std::vector<Entry> OfType(const std::vector<Entry>& all, const std::string& types) {
  std::vector<Entry> out;
  for (const Entry& e : all)
    if (types.find(e.type) != std::string::npos) out.push_back(e);
  return out;
}

int Number(const std::string& text, const std::string& after_number) {
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("(\\d+) " + after_number)));
  return std::stoi(m[1]);
}

}  // namespace

TEST_CASE("rgbdvo capture under fakenect: every frame, the true path, a faithful recording") {
  std::vector<Rigid3d> truth;
  const std::string rec = Recording(&truth);
  const std::string dir = MakeTempDir("capture");
  std::string out;
  const int code = Capture(
      rec, "--no-drop --record " + dir + "/out --csv " + dir + "/t.csv --tum " + dir + "/t.txt",
      &out);
  INFO(out);
  // End of the recording is a clean stop.
  REQUIRE(code == 0);
  CHECK_THAT(out,
             Catch::Contains(
                 "20 frames, 20 accepted, 0 recovered, 0 icp, 0 predicted, 0 rejected, 0 lost") &&
                 Catch::Contains("0 dropped") &&
                 Catch::Contains("stopped: end of the fakenect recording"));
  CHECK(Lines(dir + "/t.csv").size() == kFrames + 1);

  // Trajectory vs the true path, the colour camera's (calib.yaml is eq. 1 alone, so rgbdvo
  // reports the IR camera 2.5 cm aside, which these small turns move by under 0.1 mm). Measured:
  // 2.6 mm and 0.07 degrees at most over 18 cm (5.4 mm and 0.13 degrees on earlier commits). What
  // remains comes from the raw depth quantisation (up to 1.9 cm per step at 2.5 m) and from eq. 1
  // being exact only at 2.5 m (synthetic_kinect.hpp); the bounds, 2 cm and 1 degree, leave room for
  // SIFT differences across machines, and a frozen trajectory fails them (checked below).
  const std::vector<Rigid3d> est = ReadTumPoses(dir + "/t.txt");
  REQUIRE(est.size() == truth.size());
  double max_t = 0, max_r = 0;
  for (size_t k = 0; k < est.size(); ++k) {
    max_t = std::max(max_t, TranslationError(est[k], truth[k]));
    max_r = std::max(max_r, RotationErrorDeg(est[k], truth[k]));
  }
  INFO("max error " << max_t << " m, " << max_r << " deg");
  CHECK(max_t < 0.02);
  CHECK(max_r < 1.0);
  CHECK(truth.back().translation().norm() > 0.1);

  // --record reproduces the input: the same colour and depth frames in the same order, with
  // the same device timestamps and bytes, and the same accelerometer readings. (Wall-clock
  // times in the names are those of the replay; a- entries follow their depth frame.)
  const std::vector<Entry> in = Entries(rec), rec_out = Entries(dir + "/out");
  const std::vector<Entry> in_frames = OfType(in, "rd"), out_frames = OfType(rec_out, "rd");
  REQUIRE(out_frames.size() == in_frames.size());
  REQUIRE(in_frames.size() == 2 * kFrames);
  for (size_t i = 0; i < in_frames.size(); ++i) {
    CHECK(out_frames[i].type == in_frames[i].type);
    CHECK(out_frames[i].device_ts == in_frames[i].device_ts);
    CHECK(out_frames[i].bytes == in_frames[i].bytes);
  }
  const std::vector<Entry> in_accel = OfType(in, "a"), out_accel = OfType(rec_out, "a");
  REQUIRE(out_accel.size() == in_accel.size());
  for (size_t i = 0; i < in_accel.size(); ++i) CHECK(out_accel[i].bytes == in_accel[i].bytes);

  // `rgbdvo run` on the recording gives the live trajectory, line for line.
  std::string run_out;
  REQUIRE(RunCommand(RgbdvoExe() + " run " + dir + "/out --calib " + rec + "/calib.yaml --tum " +
                         dir + "/r.txt --quiet",
                     &run_out) == 0);
  CHECK(Slurp(dir + "/r.txt") == Slurp(dir + "/t.txt"));

  // And the recording replays through fakenect again.
  std::string again;
  CHECK(Capture(dir + "/out", "--no-drop --quiet --frames 3", &again) == 0);
  CHECK_THAT(again, Catch::Contains("3 frames, 3 accepted"));
}

TEST_CASE("rgbdvo capture --gravity gives every frame the device's accelerometer reading") {
  std::string out;
  const int code = Capture(Recording(), "--no-drop --gravity --quiet", &out);
  INFO(out);
  REQUIRE(code == 0);
  // The synthetic Kinect's readings are gravity alone (weight 1) and agree with the path the
  // odometry measures (measured: largest tilt 0.51 degrees by default, 0.49 with Lowe's SIFT
  // detector on the 2x-upsampled image; ATE 1.3 and 1.4 mm).
  CHECK_THAT(out, Catch::Contains("gravity: 20 frames with an accelerometer reading, mean "
                                  "weight 1.00"));
  std::smatch m;
  REQUIRE(std::regex_search(out, m, std::regex("largest tilt against a reading ([0-9.]+) deg")));
  CHECK(std::stod(m[1]) < 0.6);
}

TEST_CASE("rgbdvo capture --frames N stops after N frames and records exactly those") {
  const std::string rec = Recording();
  const std::string dir = MakeTempDir("capture_n");
  std::string out;
  REQUIRE(Capture(rec, "--no-drop --frames 4 --record " + dir + "/out --csv " + dir + "/t.csv",
                  &out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("4 frames") && Catch::Contains("stopped: 4 frames"));
  CHECK(Lines(dir + "/t.csv").size() == 5);
  FakenectSource replay(dir + "/out", {});
  CHECK(replay.size() == 4);
}

TEST_CASE("rgbdvo capture drops frames when behind, counts them, and still records all") {
  // Whether frames are dropped depends on the machine's speed; what must hold either way:
  // every colour frame is paired or counted as without depth, every pair is processed or
  // counted as dropped, the trajectory has a row per processed frame, and the recording keeps
  // every frame.
  const std::string rec = Recording();
  const std::string dir = MakeTempDir("capture_drop");
  std::string out;
  REQUIRE(Capture(rec, "--queue 1 --record " + dir + "/out --csv " + dir + "/t.csv", &out) == 0);
  INFO(out);
  const int pairs = Number(out, "pairs");
  const int processed = Number(out, "processed");
  const int dropped = Number(out, "dropped \\(odometry behind\\)");
  const int unpaired = Number(out, "colour frames without depth");
  CHECK(pairs + unpaired == kFrames);
  CHECK(processed + dropped == pairs);
  CHECK(processed >= 1);
  CHECK(static_cast<int>(Lines(dir + "/t.csv").size()) == processed + 1);
  CHECK(OfType(Entries(dir + "/out"), "rd").size() == 2 * kFrames);
}

TEST_CASE("rgbdvo capture with an odometry slower than the stream: the newest frame wins") {
  // The hidden --debug-frame-delay-ms makes every frame take at least 300 ms on the main thread
  // (10x a 30 Hz frame period). No bound below depends on the machine's speed: the stream's
  // duration is measured from the recording's host times.
  const std::string rec = Recording();
  const std::string dir = MakeTempDir("capture_slow");
  std::string out;
  REQUIRE(Capture(rec,
                  "--queue 1 --threads 2 --debug-frame-delay-ms 300 --record " + dir +
                      "/out --tum " + dir + "/t.txt",
                  &out) == 0);
  INFO(out);
  const int pairs = Number(out, "pairs");
  const int processed = Number(out, "processed");
  const int dropped = Number(out, "dropped \\(odometry behind\\)");
  CHECK(processed + dropped == pairs);
  const std::vector<std::string> rows = Lines(dir + "/t.txt");
  REQUIRE(static_cast<int>(rows.size()) == processed + 1);  // + the header

  // Host arrival times of the first and the last frame (r-/d- entries).
  std::vector<double> times;
  std::vector<double> depth_times;
  for (const std::string& name : ReadFakenectIndex(dir + "/out/INDEX.txt")) {
    const auto n = ParseFakenectName(name);
    REQUIRE(n);
    if (n->type == 'r' || n->type == 'd') times.push_back(n->seconds());
    if (n->type == 'd') depth_times.push_back(n->seconds());
  }
  REQUIRE(times.size() == 2 * kFrames);
  const double stream_s = times.back() - times.front();
  // Read-ahead is bounded: while the stream ran the odometry finished at most stream_s / 0.3 s
  // frames and had one more in hand; when it ended, at most the source queue (1) and one frame
  // per worker (2) were waiting, and the pairer's last pair can come just after (1). Anything
  // beyond would be a backlog kept out of the source queue, where the oldest is dropped.
  const int bound = static_cast<int>(stream_s / 0.3) + 1 + 1 + 2 + 1;
  INFO("stream " << stream_s << " s, at most " << bound << " frames can be processed");
  CHECK(processed <= bound);
  if (bound < pairs) CHECK(dropped > 0);
  // The newest frame wins: the last pair is processed (its pose has the last depth time).
  std::istringstream last(rows.back());
  double t_last = 0;
  last >> t_last;
  CHECK(t_last == Approx(depth_times.back()).margin(2e-6));
}

TEST_CASE("rgbdvo capture stops cleanly on Ctrl-C with its outputs complete") {
  const std::string rec = Recording();
  const std::string dir = MakeTempDir("capture_int");
  // fakenect's wrapper script would receive the signal, so set its environment directly.
  const std::string script =
      "lib=$(sed -n 's/.*LD_LIBRARY_PATH=\"\\([^:]*\\):.*/\\1/p' \"$(command -v fakenect)\" | head "
      "-n 1); "
      "FAKENECT_PATH=" +
      rec + " LD_LIBRARY_PATH=$lib " + RgbdvoExe() + " capture --calib " + rec +
      "/calib.yaml --no-drop --record " + dir + "/out --csv " + dir + "/t.csv --tum " + dir +
      "/t.txt & pid=$!; "
      "for i in $(seq 600); do [ \"$(wc -l < " +
      dir +
      "/t.csv 2>/dev/null || echo 0)\" -ge 3 ] "
      "&& break; sleep 0.1; done; kill -INT $pid; wait $pid; echo exit=$?";
  std::string out;
  RunCommand("sh -c '" + std::regex_replace(script, std::regex("'"), "'\\''") + "'", &out);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("exit=0") && Catch::Contains("stopped: stop requested"));
  const std::vector<std::string> rows = Lines(dir + "/t.csv");
  REQUIRE(rows.size() >= 3);
  for (const std::string& row : rows) CHECK(std::count(row.begin(), row.end(), ',') == 11);
  // The recording is usable and replays into the same trajectory.
  std::string run_out;
  REQUIRE(RunCommand(RgbdvoExe() + " run " + dir + "/out --calib " + rec + "/calib.yaml --tum " +
                         dir + "/r.txt --quiet",
                     &run_out) == 0);
  CHECK(Slurp(dir + "/r.txt") == Slurp(dir + "/t.txt"));
}

TEST_CASE("rgbdvo capture without a Kinect is a clear error") {
  freenect_context* ctx = nullptr;
  if (freenect_init(&ctx, nullptr) >= 0) {
    const int devices = freenect_num_devices(ctx);
    freenect_shutdown(ctx);
    if (devices > 0) {
      WARN("a Kinect is connected; the no-device test does not apply");
      return;
    }
  }
  const std::string dir = MakeTempDir("nodevice");
  std::string out;
  const int code = RunCommand("env -u FAKENECT_PATH " + RgbdvoExe() + " capture --calib " +
                                  SourceDir() + "/calib/kinect_v1_default.yaml --frames 1 --csv " +
                                  dir + "/t.csv --record " + dir + "/rec",
                              &out);
  INFO(out);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::StartsWith("rgbdvo: error:") && Catch::Contains("Kinect"));
  CHECK(!fs::exists(dir + "/rec"));  // no empty recording left behind to block a retry
}

TEST_CASE("rgbdvo capture --record refuses an existing recording and changes nothing") {
  const std::string rec = Recording();
  const std::string index_before = Slurp(rec + "/INDEX.txt");
  std::string out;
  CHECK(Capture(rec, "--record " + rec, &out) == 1);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("refusing to overwrite"));
  CHECK(Slurp(rec + "/INDEX.txt") == index_before);
}

TEST_CASE("rgbdvo run on a fakenect folder: truncated depth stops the run, rows kept") {
  const std::string rec = MakeTempDir("run_fakenect") + "/rec";
  SyntheticKinectOptions o;
  o.color = {131.25, 131.25, 79.5, 59.5, 160, 120};
  o.ir = {145.0, 145.0, 80.0, 60.0, 160, 120};
  WriteSyntheticKinectRecording(rec, SyntheticScene(), o, MakeKinectRangePath(4));
  const std::vector<std::string> names = ReadFakenectIndex(rec + "/INDEX.txt");
  fs::resize_file(rec + "/" + names[8], 100);  // depth of frame 2 (r a d per frame)
  std::string out;
  const int code = RunCommand(RgbdvoExe() + " run " + rec + " --calib " + rec +
                                  "/calib.yaml --min-inliers 5 --csv " + rec + "/t.csv",
                              &out);
  INFO(out);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains(names[8]) && Catch::Contains("truncated"));
  CHECK(Lines(rec + "/t.csv").size() == 3);  // header + frames 0 and 1
}

TEST_CASE("rgbdvo capture killed with SIGKILL leaves a recording that lists only complete files") {
  const std::string rec = Recording();
  const std::string dir = MakeTempDir("capture_kill");
  // As the Ctrl-C test, with 200 ms per frame so the kill lands mid-recording.
  const std::string script =
      "lib=$(sed -n 's/.*LD_LIBRARY_PATH=\"\\([^:]*\\):.*/\\1/p' \"$(command -v fakenect)\" | head "
      "-n 1); "
      "FAKENECT_PATH=" +
      rec + " LD_LIBRARY_PATH=$lib " + RgbdvoDebugExe() + " capture --calib " + rec +
      "/calib.yaml --no-drop --debug-frame-delay-ms 200 --record " + dir + "/out --csv " + dir +
      "/t.csv & pid=$!; "
      "for i in $(seq 600); do [ \"$(cat " +
      dir +
      "/t.csv 2>/dev/null | wc -l)\" -ge 4 ] "
      "&& break; sleep 0.1; done; kill -KILL $pid; wait $pid; echo exit=$?";
  std::string out;
  RunCommand("sh -c '" + std::regex_replace(script, std::regex("'"), "'\\''") + "'", &out);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("exit=137"));
  // Every file INDEX.txt names is there, whole: its header's size of pixels follows it.
  const std::vector<std::string> names = ReadFakenectIndex(dir + "/out/INDEX.txt");
  REQUIRE(names.size() >= 3);
  for (const std::string& name : names) {
    INFO(name);
    const std::string path = dir + "/out/" + name;
    REQUIRE(fs::exists(path));
    if (name[0] == 'r') CHECK(ReadFakenectColor(path).total() == 640 * 480);
    if (name[0] == 'd') CHECK(ReadFakenectDepth(path).total() == 640 * 480);
  }
  for (const std::string& row : Lines(dir + "/t.csv"))
    CHECK(std::count(row.begin(), row.end(), ',') == 11);
}
