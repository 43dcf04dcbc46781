#include "run_common.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <opencv2/core/utility.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "rgbdvo/pipeline/run_parameters.hpp"
#include "rgbdvo/util/display_text.hpp"

namespace rgbdvo::cli {

void TrajectoryOutputs::AddFlags(CLI::App* cmd) {
  cmd->add_option("--csv", csv,
                  "trajectory CSV with each frame's status, written frame by frame (- = standard "
                  "output)");
  // The old name of --csv (ambiguous beside --tum and --kitti): still accepted, with a warning.
  cmd->add_option("--out", csv, "deprecated: --csv")->group("")->each([](const std::string&) {
    std::cerr << "rgbdvo: warning: --out is deprecated and will be removed; use --csv" << std::endl;
  });
  cmd->add_option("--tum", tum,
                  "trajectory in TUM format (timestamp tx ty tz qx qy qz qw; - = standard output)");
  cmd->add_option("--kitti", kitti,
                  "trajectory in KITTI format (3x4 camera-to-world matrix a line, no timestamps; - "
                  "= standard output)");
  cmd->add_option("--stamp", stamp,
                  "time of each trajectory row: color (the colour image's: the pose as estimated, "
                  "a row per frame) or depth (the paired depth image's: the pose moved there at "
                  "the frame's velocity; a frame whose depth time repeats an earlier row's is "
                  "left out of --tum and --kitti)")
      ->capture_default_str()
      ->check(CLI::IsMember({"color", "depth"}));
}

void AddPairingFlag(CLI::App* cmd, std::string* pairing) {
  cmd->add_option("--pairing", *pairing,
                  "colour-depth pairing: nearest (each colour image takes the nearest depth "
                  "image; two can share one) or one-to-one (as the TUM tools' associate.py: "
                  "closest pairs first, each image used once; a colour image left without depth "
                  "is dropped)")
      ->capture_default_str()
      ->check(CLI::IsMember({"nearest", "one-to-one"}));
}

std::vector<std::unique_ptr<TrajectoryWriter>> TrajectoryOutputs::Open() const {
  std::vector<std::unique_ptr<TrajectoryWriter>> writers;
  const StampTime when = ParseStampTime(stamp);
  if (!csv.empty()) writers.push_back(std::make_unique<CsvTrajectoryWriter>(csv, when));
  if (!tum.empty()) writers.push_back(std::make_unique<TumTrajectoryWriter>(tum, when));
  if (!kitti.empty()) writers.push_back(std::make_unique<KittiTrajectoryWriter>(kitti, when));
  return writers;
}

void TrajectoryOutputs::RefuseInputs(const std::vector<std::string>& inputs,
                                     const std::vector<OutputPath>& others) const {
  std::vector<OutputPath> outputs = {{csv, "--csv"}, {tum, "--tum"}, {kitti, "--kitti"}};
  outputs.insert(outputs.end(), others.begin(), others.end());
  RefuseOutputsOntoInputs(outputs, inputs);
}

void LimitOpenCvThreads() {
  // One thread: one core. N feature workers already keep every core busy, so OpenCV's own
  // parallel loops (cvtColor and the like, inside each worker) would only add threads that
  // compete with them (docs/decisions/0001-own-sift-guided-matching-workers.md).
  cv::setNumThreads(1);
}

namespace {
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "used in a signal handler");
struct sigaction g_previous_int = {}, g_previous_term = {};

extern "C" void OnStopSignal(int signo) {
  g_signal = signo;
  g_stop = true;
  signal(SIGINT, SIG_DFL);  // a second signal ends the process
  signal(SIGTERM, SIG_DFL);
}
}  // namespace

StopOnSignals::StopOnSignals(std::chrono::milliseconds deadline) {
  g_stop = false;
  g_signal = 0;
  struct sigaction action = {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
  if (deadline.count() <= 0) return;
  // A thread that polls: a signal handler can neither start one nor wake one safely.
  watchdog_ = std::thread([this, deadline] {
    constexpr auto kPoll = std::chrono::milliseconds(50);
    while (!done_ && !g_stop) std::this_thread::sleep_for(kPoll);
    for (auto waited = std::chrono::milliseconds(0); !done_ && waited < deadline; waited += kPoll)
      std::this_thread::sleep_for(kPoll);
    if (done_) return;
    const int signo = g_signal;
    const std::string line = std::string("rgbdvo: stopped by ") +
                             (signo == SIGINT ? "SIGINT" : "SIGTERM") +
                             " before the frames in hand were done; every row written is whole\n";
    [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, line.data(), line.size());
    _exit(128 + signo);
  });
}

StopOnSignals::~StopOnSignals() {
  done_ = true;
  if (watchdog_.joinable()) watchdog_.join();
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

std::atomic<bool>& StopOnSignals::Flag() { return g_stop; }
int StopOnSignals::Signal() { return g_signal; }

std::optional<Frame> StoppableSource::Next() {
  if (StopOnSignals::Flag()) return std::nullopt;
  return inner_.Next();
}

StatusLine::StatusLine(bool quiet, std::optional<size_t> total)
    : quiet_(quiet),
      terminal_(!quiet && isatty(STDERR_FILENO)),
      total_(total),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

std::string StatusLine::Text(const FrameResult& r, const std::string& extra) const {
  const double seconds = std::chrono::duration<double>(last_print_ - start_).count();
  const double fps = seconds > 0 ? done_ / seconds : 0;
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << "frame " << r.frame;
  if (total_)
    s << " (" << done_ << "/" << *total_ << ", " << 100 * done_ / std::max<size_t>(1, *total_)
      << " %)";
  const std::string status = r.StatusString();
  s << ", " << fps << " fps, " << r.inliers << " inliers, " << status.substr(0, status.find(':'));
  if (total_ && fps > 0 && *total_ > done_)
    s << ", " << std::lround((*total_ - done_) / fps) << " s left";
  return s.str() + extra;
}

void StatusLine::Update(const FrameResult& r, const std::string& extra) {
  if (quiet_) return;
  ++done_;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_print_).count();
  if (since < (terminal_ ? 0.1 : 10.0)) return;
  last_print_ = now;
  if (terminal_) {
    std::cerr << "\r" << Text(r, extra) << "\x1b[K" << std::flush;  // erase the rest of the line
  } else {
    std::cerr << "rgbdvo: " << Text(r, extra) << std::endl;
  }
  printed_ = true;
}

void StatusLine::Finish() {
  if (terminal_ && printed_) std::cerr << "\n";
}

std::string MotionModelSummary(const Odometry& odometry, const RunSummary& summary) {
  if (!odometry.level_from_cam()) return "";
  return "motion model: " + odometry.MotionModelBrief() + "; left the plane " +
         std::to_string(summary.non_planar_episodes) + " times (" +
         std::to_string(summary.non_planar_frames) + " frames)";
}

std::function<void(const std::string&)> PrintWarning(bool progress) {
  return [progress](const std::string& warning) {
    std::cerr << (progress ? "\n" : "") << "rgbdvo: warning: " << Printable(warning) << std::endl;
  };
}

void PrintConfiguration(std::ostream& out, const std::string& source, const std::string& calib_path,
                        const Calibration& calib, const OdometryOptions& options,
                        const RunOptions& run) {
  out << "# rgbdvo " RGBDVO_VERSION "\n# source: " << source << "\n# calibration: " << calib_path
      << " A=" << calib.A << " B=" << calib.B << " C=" << calib.C << " D=" << calib.D;
  if (calib.HasDisparityTerm()) out << " s_u=" << calib.s_u << " s_v=" << calib.s_v;
  out << " fx=" << calib.fx << " fy=" << calib.fy << " cx=" << calib.cx << " cy=" << calib.cy
      << " depth=[" << calib.min_depth_m << "," << calib.max_depth_m
      << "] m\n# threads: " << run.Describe() << "\n";
  std::istringstream config(ConfigurationText(options, run));
  for (std::string line; std::getline(config, line);) out << "# " << line << "\n";
}

}  // namespace rgbdvo::cli
