// `rgbdvo run RECORDING`: visual odometry over a recorded folder or a ROS bag.
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "debug_flags.hpp"
#include "recording_input.hpp"
#include "rgbdvo/evaluation/plot.hpp"
#include "rgbdvo/pipeline/run.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sensor/calibration_catalog.hpp"
#include "rgbdvo/sources/frame_range.hpp"
#include "rgbdvo/sources/open_source.hpp"
#include "run_common.hpp"

namespace rgbdvo::cli {
namespace {

struct RunArgs {
  RecordingArgs recording;
  std::string plot;
  TrajectoryOutputs outputs;
  bool quiet = false, timing = false;
  int frame_delay_ms = 0;  // tests only (debug_flags.hpp): an odometry this much slower
  FrameRange range;
  std::unique_ptr<ConfigurationFlags> configuration_flags;
};

// Keeps the poses in memory for --plot, stamped as the files are.
struct PoseRecorder : TrajectoryWriter {
  explicit PoseRecorder(StampTime stamp) : stamp(stamp) {}
  StampTime stamp;
  std::vector<StampedPose> poses;
  void Write(const FrameResult& r) override { poses.push_back(StampRow(r, stamp)); }
};

int Run(const RunArgs& a) {
  if (a.configuration_flags->dump_requested()) {
    std::cout << a.configuration_flags->DumpConfig() << std::flush;
    return 0;
  }
  if (a.recording.path.empty()) throw CLI::RequiredError("recording");
  const Configuration configuration = a.configuration_flags->Resolve();
  const OdometryOptions& odometry_options = configuration.odometry;
  const RunOptions& run_options = configuration.run;
  RecordingArgs recording_args = a.recording;
  recording_args.source.tum.accelerometer = recording_args.source.fakenect.accelerometer =
      odometry_options.NeedsAccelerometer();
  Recording recording = OpenRecordingInput(recording_args);
  const Calibration& calib = recording.calib;
  const auto source = std::make_unique<FrameRangeSource>(std::move(recording.source), a.range);
  std::vector<std::string> inputs = recording.inputs;
  const std::vector<std::string> images = source->Files();
  inputs.insert(inputs.end(), images.begin(), images.end());
  inputs.push_back(a.configuration_flags->config_path());
  a.outputs.RefuseInputs(inputs, {{a.plot, "--plot"}});
  // With a trajectory on standard output ("-"), everything else goes to stderr.
  std::ostream& info = a.outputs.UsesStdout() ? std::cerr : std::cout;
  if (a.outputs.csv.empty() && a.outputs.tum.empty() && a.outputs.kitti.empty() && a.plot.empty())
    std::cerr << "rgbdvo: warning: no --csv, --tum, --kitti or --plot: the trajectory is computed "
                 "but not written\n";
  const std::vector<std::unique_ptr<TrajectoryWriter>> writers = a.outputs.Open();
  std::vector<TrajectoryWriter*> writer_ptrs;
  writer_ptrs.reserve(writers.size() + 1);
  for (auto& w : writers) writer_ptrs.push_back(w.get());
  PoseRecorder recorder(ParseStampTime(a.outputs.stamp));
  if (!a.plot.empty()) writer_ptrs.push_back(&recorder);

  if (!a.quiet) {
    PrintConfiguration(info, source->Describe(), recording.calib_source, calib, odometry_options,
                       run_options);
    info << std::flush;
  }
  LimitOpenCvThreads();
  Odometry odometry(odometry_options, calib);
  const StopOnSignals stop_on_signals(std::chrono::seconds(1));
  StoppableSource stoppable(*source);
  StatusLine status(a.quiet, stoppable.Size());
  const RunSummary summary = RunOdometry(
      stoppable, odometry, writer_ptrs,
      [&](const FrameResult& r) {
        if (r.status == FrameStatus::kFirst && !a.quiet)
          info << "# motion model: " << odometry.MotionModelBrief() << std::endl;
        status.Update(r);
        DelayFrame(a.frame_delay_ms);
      },
      run_options, PrintWarning(status.redrawn()));
  status.Finish();
  info << summary.Brief() << std::endl;
  if (const std::string model = MotionModelSummary(odometry, summary); !model.empty())
    info << model << std::endl;
  if (const std::string gravity = odometry.GravityBrief(); !gravity.empty())
    info << gravity << std::endl;
  if (const int signo = StopOnSignals::Signal(); signo != 0) {
    // Interrupted: what was computed is written; the exit code says the run is incomplete, as a
    // shell reports a command ended by that signal.
    std::cerr << "rgbdvo: interrupted by " << (signo == SIGINT ? "SIGINT" : "SIGTERM") << " after "
              << summary.frames << " frames; every one of them is in the trajectory files"
              << std::endl;
    return 128 + signo;
  }
  if (a.timing) info << summary.Timing() << "\n" << summary.Matching() << std::endl;
  if (!a.plot.empty()) {  // with the folder's groundtruth.txt when it has one
    std::vector<StampedPose> gt;
    if (!recording.groundtruth.empty() && std::filesystem::exists(recording.groundtruth))
      gt = ReadTrajectory(recording.groundtruth).poses;
    PlotOptions plot;
    plot.title = "rgbdvo run " + a.recording.path;
    info << PlotTrajectory(recorder.poses, gt, a.plot, plot).Brief() << std::endl;
  }
  return 0;
}

}  // namespace

void AddRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run", "visual odometry over a recording (TUM RGB-D or fakenect folder, or a ROS 1 bag)");
  // Required unless --dump-config (checked by Run).
  cmd->add_option("recording", args->recording.path, "recording folder or ROS bag file (required)");
  args->recording.AddFlags(cmd);
  args->outputs.AddFlags(cmd);
  cmd->add_option("--start", args->range.start,
                  "first frame (colour-depth pair, counted from 0); rows keep the recording's "
                  "frame numbers")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-frames", args->range.max_frames, "at most N frames (0 = to the end)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--plot", args->plot, "PNG of the path after the run (with ground truth if any)");
  cmd->add_flag("--quiet", args->quiet, "print only the summary line");
  cmd->add_flag("--timing", args->timing, "also print milliseconds per frame for each stage");
  AddFrameDelayFlag(cmd, &args->frame_delay_ms);
  args->configuration_flags = std::make_unique<ConfigurationFlags>(cmd, RunOptions{});
  cmd->callback([args] {
    const int code = Run(*args);
    if (code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace rgbdvo::cli
