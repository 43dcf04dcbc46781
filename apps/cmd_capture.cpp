// `rgbdvo capture`: visual odometry live from a Kinect v1 (libfreenect), optionally recording.
#include <unistd.h>

#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "rgbdvo/sensor/calibration_catalog.hpp"

#if !RGBDVO_WITH_KINECT

#include <stdexcept>

namespace rgbdvo::cli {

// Built without libfreenect (cmake -DRGBDVO_WITH_KINECT=OFF): the command says so.
void AddCaptureCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("capture", "live capture (not in this build: no libfreenect)");
  cmd->allow_extras();
  cmd->callback([] {
    throw std::runtime_error(
        "this rgbdvo was built without Kinect capture (rebuild with -DRGBDVO_WITH_KINECT=ON, "
        "which needs libfreenect-dev)");
  });
}

}  // namespace rgbdvo::cli

#else

#include "debug_flags.hpp"
#include "rgbdvo/capture/kinect_source.hpp"
#include "rgbdvo/pipeline/run.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/util/display_text.hpp"
#include "run_common.hpp"

namespace rgbdvo::cli {
namespace {

struct CaptureArgs {
  std::string calib, pairing = "nearest";
  TrajectoryOutputs outputs;
  bool quiet = false, no_drop = false, no_accel = false;
  int frame_delay_ms = 0;  // tests only (debug_flags.hpp): an odometry this much slower
  KinectSourceOptions kinect;
  std::unique_ptr<ConfigurationFlags> configuration_flags;
};

constexpr int kExitDeviceLost = 3;

int Capture(CaptureArgs& a) {
  if (a.configuration_flags->dump_requested()) {
    std::cout << a.configuration_flags->DumpConfig() << std::flush;
    return 0;
  }
  if (a.calib.empty()) throw CLI::RequiredError("--calib");
  const Configuration configuration = a.configuration_flags->Resolve();
  const OdometryOptions& odometry_options = configuration.odometry;
  const RunOptions& run_options = configuration.run;
  const std::string calib_path = FindCalibration(a.calib);
  const Calibration calib = LoadCalibration(calib_path);
  a.kinect.drop_when_behind = !a.no_drop;
  a.kinect.record_accel = !a.no_accel;
  a.kinect.read_accel = odometry_options.NeedsAccelerometer();
  a.kinect.stop = &StopOnSignals::Flag();
  a.kinect.pairing = ParsePairing(a.pairing);
  a.kinect.Check();
  a.outputs.RefuseInputs({calib_path, a.configuration_flags->config_path()});
  // With a trajectory on standard output ("-"), everything else goes to stderr.
  std::ostream& info = a.outputs.UsesStdout() ? std::cerr : std::cout;
  const std::vector<std::unique_ptr<TrajectoryWriter> > writers = a.outputs.Open();
  std::vector<TrajectoryWriter*> writer_ptrs;
  writer_ptrs.reserve(writers.size());
  for (auto& w : writers) writer_ptrs.push_back(w.get());

  // Ctrl-C (or SIGTERM from a supervisor) is how a capture ends: cleanly, exit 0.
  const StopOnSignals stop_on_signals;

  KinectSource source(a.kinect);
  if (!a.quiet) {
    PrintConfiguration(info, source.Describe(), calib_path, calib, odometry_options, run_options);
    info << "# Ctrl-C (or SIGTERM) stops cleanly" << std::endl;
  }
  LimitOpenCvThreads();
  Odometry odometry(odometry_options, calib);
  StatusLine status(a.quiet, std::nullopt);
  const bool progress = status.redrawn();
  int warned_at = 0;
  const auto on_frame = [&](const FrameResult& r) {
    const int dropped = source.stats().dropped;
    if (dropped > 0 && (warned_at == 0 || dropped >= warned_at + 30)) {
      std::cerr << (progress ? "\n" : "") << "rgbdvo: warning: the odometry is slower than the "
                << "camera; " << dropped << " frames dropped so far (the newest frame wins)"
                << std::endl;
      warned_at = dropped;
    }
    if (r.status == FrameStatus::kFirst && !a.quiet)
      info << "# motion model: " << odometry.MotionModelBrief() << std::endl;
    status.Update(r, ", " + std::to_string(dropped) + " dropped");
    DelayFrame(a.frame_delay_ms);
  };
  const RunSummary summary =
      RunOdometry(source, odometry, writer_ptrs, on_frame, run_options, PrintWarning(progress));
  status.Finish();
  const CaptureStats stats = source.stats();
  info << summary.Brief() << "; " << stats.Brief() << std::endl;
  if (const std::string model = MotionModelSummary(odometry, summary); !model.empty())
    info << model << std::endl;
  if (const std::string gravity = odometry.GravityBrief(); !gravity.empty())
    info << gravity << std::endl;
  if (stats.end == CaptureEnd::kDeviceLost) {
    std::cerr << "rgbdvo: error: " << Printable(stats.end_reason)
              << "; the trajectory and recording so far are complete and usable" << std::endl;
    return kExitDeviceLost;
  }
  return 0;
}

}  // namespace

void AddCaptureCommand(CLI::App& app) {
  auto args = std::make_shared<CaptureArgs>();
  CLI::App* cmd = app.add_subcommand(
      "capture", "visual odometry live from a Kinect v1 (libfreenect), optionally recording it");
  cmd->add_option("--device", args->kinect.device, "libfreenect device index")
      ->capture_default_str();
  // Required unless --dump-config (checked by Capture).
  AddCalibFlag(cmd, &args->calib,
               "calibration YAML (required; uncalibrated Kinect: kinect_v1_default)");
  cmd->add_option("--frames", args->kinect.max_frames, "stop after N frames (0 = until Ctrl-C)")
      ->capture_default_str();
  cmd->add_option("--seconds", args->kinect.max_seconds, "stop after S seconds (0 = until Ctrl-C)")
      ->capture_default_str();
  cmd->add_option("--record", args->kinect.record_folder,
                  "record into this new folder (fakenect layout; never overwrites)");
  cmd->add_flag("--no-accel", args->no_accel, "do not record accelerometer entries");
  args->outputs.AddFlags(cmd);
  cmd->add_option("--max-dt", args->kinect.max_time_diff_s, "max colour-depth time difference, s")
      ->capture_default_str();
  AddPairingFlag(cmd, &args->pairing);
  cmd->add_option("--queue", args->kinect.queue_capacity,
                  "frames waiting for the odometry; when full the oldest is dropped")
      ->capture_default_str();
  cmd->add_flag("--no-drop", args->no_drop,
                "wait for the odometry instead of dropping frames (for fakenect replays)");
  cmd->add_flag("--quiet", args->quiet, "print only the summary line");
  AddFrameDelayFlag(cmd, &args->frame_delay_ms);
  // Read no further ahead than the workers need: a backlog then waits in the source's queue,
  // where the oldest pair is dropped and counted (the newest frame wins).
  RunOptions run_defaults;
  run_defaults.queue_frames = 1;
  args->configuration_flags = std::make_unique<ConfigurationFlags>(cmd, run_defaults);
  cmd->callback([args] {
    const int code = Capture(*args);
    if (code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace rgbdvo::cli

#endif  // RGBDVO_WITH_KINECT
