#pragma once
// What `run` and `capture` share: the trajectory output flags, --threads and the configuration
// header.

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "output_paths.hpp"
#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/pipeline/run.hpp"
#include "rgbdvo/pipeline/trajectory_writer.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame_source.hpp"

namespace rgbdvo::cli {

struct TrajectoryOutputs {
  std::string csv, tum, kitti;
  std::string stamp = "color";   // --stamp, as ParseStampTime takes it
  void AddFlags(CLI::App* cmd);  // --csv (--out), --tum, --kitti, --stamp
  // Throws naming the file when an output (these and `others`, such as --plot) is one of
  // `inputs` or two outputs are the same file: writing would destroy what the run reads.
  void RefuseInputs(const std::vector<std::string>& inputs,
                    const std::vector<OutputPath>& others = {}) const;
  bool UsesStdout() const { return csv == "-" || tum == "-" || kitti == "-"; }
  // A writer per file given; throws naming a file that cannot be written.
  std::vector<std::unique_ptr<TrajectoryWriter>> Open() const;
};

// --pairing into *pairing ("nearest" or "one-to-one", as ParsePairing takes it).
void AddPairingFlag(CLI::App* cmd, std::string* pairing);

// Turns OpenCV's own parallel loops off: our threads (one, or the feature workers) are the
// parallelism.
void LimitOpenCvThreads();

// SIGINT and SIGTERM while an instance lives: the first one only sets a flag (the run finishes
// the frame in hand, writes it and stops, so nothing computed is lost); a second one ends the
// process the default way. With a `deadline`, a process still running that long after the first
// signal ends itself (exit 128 + the signal, one line saying so): every row written is whole,
// so only the frames in hand are lost, and a watchdog's signal always stops a run in time. The
// previous handlers are restored on destruction.
class StopOnSignals {
 public:
  explicit StopOnSignals(std::chrono::milliseconds deadline = std::chrono::milliseconds(0));
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;
  // Set by the first signal; for sources that poll a flag (KinectSourceOptions::stop).
  static std::atomic<bool>& Flag();
  static int Signal();  // the signal's number, 0 while none came

 private:
  std::atomic<bool> done_{false};
  std::thread watchdog_;  // with a deadline: ends the process that long after the first signal
};

// `inner` until StopOnSignals::Flag() is set, then the end (the frames in flight still finish).
class StoppableSource : public FrameSource {
 public:
  explicit StoppableSource(FrameSource& inner) : inner_(inner) {}
  std::optional<Frame> Next() override;
  std::string Describe() const override { return inner_.Describe(); }
  std::optional<size_t> Size() const override { return inner_.Size(); }

 private:
  FrameSource& inner_;
};

// The status of a run on stderr: on a terminal one line redrawn in place (at most 10 times a
// second), otherwise a plain line every 10 s; nothing when quiet. "frame 123/798 (15 %), 31.2
// fps, 245 inliers, accepted, 21 s left" (the total and time left when the source knows its
// size); `extra` is appended (capture's dropped frames).
class StatusLine {
 public:
  StatusLine(bool quiet, std::optional<size_t> total);
  void Update(const FrameResult& result, const std::string& extra = "");
  void Finish();  // ends the redrawn line
  bool redrawn() const { return terminal_; }

 private:
  std::string Text(const FrameResult& result, const std::string& extra) const;
  bool quiet_, terminal_;
  std::optional<size_t> total_;
  size_t done_ = 0;
  std::chrono::steady_clock::time_point start_, last_print_;
  bool printed_ = false;
};

// A run's on_warning: "rgbdvo: warning: ..." on stderr, on a fresh line when a progress line
// (`progress`) is being redrawn there.
std::function<void(const std::string&)> PrintWarning(bool progress);

// With the planar motion model, after the run: "motion model: <the model and its floor>; left
// the plane N times (M frames)"; empty with 6-DOF.
std::string MotionModelSummary(const Odometry& odometry, const RunSummary& summary);

// The effective configuration as `# ` lines, so a run can be reproduced.
void PrintConfiguration(std::ostream& out, const std::string& source, const std::string& calib_path,
                        const Calibration& calib, const OdometryOptions& options,
                        const RunOptions& run);

}  // namespace rgbdvo::cli
