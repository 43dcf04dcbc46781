// `rgbdvo run FOLDER`: visual odometry over a recorded folder.
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
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
  std::string folder, calib, plot;
  TrajectoryOutputs outputs;
  bool quiet = false, timing = false;
  int frame_delay_ms = 0;  // hidden, for tests: an odometry this much slower per frame
  RunOptions run;
  SourceOptions source;
  FrameRange range;
  bool depth_scale_given = false;
  std::unique_ptr<OdometryFlags> odometry_flags;
};

// Keeps the poses in memory for --plot.
struct PoseRecorder : TrajectoryWriter {
  std::vector<StampedPose> poses;
  void Write(const FrameResult& r) override { poses.push_back({r.timestamp, r.world_from_cam}); }
};

int Run(const RunArgs& a) {
  if (a.odometry_flags->dump_requested()) {
    std::cout << a.odometry_flags->DumpConfig() << std::flush;
    return 0;
  }
  if (a.folder.empty()) throw CLI::RequiredError("folder");
  if (a.calib.empty()) throw CLI::RequiredError("--calib");
  const OdometryOptions odometry_options = a.odometry_flags->Resolve();
  const std::string calib_path = FindCalibration(a.calib);
  const Calibration calib = LoadCalibration(calib_path);
  // The depth scale: --depth-scale, else the calibration's, else TUM's 5000.
  SourceOptions source_options = a.source;
  if (!a.depth_scale_given && calib.depth_units_per_m > 0)
    source_options.tum.depth_units_per_m = calib.depth_units_per_m;
  std::unique_ptr<FrameSource> recording = OpenRecording(a.folder, source_options);
  if (auto* tum = dynamic_cast<TumSource*>(recording.get()); tum && !tum->unpaired().empty()) {
    std::cerr << "rgbdvo: skipping " << tum->unpaired().size()
              << " rgb frames without a depth frame within " << a.source.tum.max_time_diff_s
              << " s (first: " << tum->unpaired().front().path << ")\n";
  }
  const auto source = std::make_unique<FrameRangeSource>(std::move(recording), a.range);
  std::vector<std::string> inputs = {calib_path};
  for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt", "accelerometer.txt",
                           "INDEX.txt", "associations.txt"})
    inputs.push_back((std::filesystem::path(a.folder) / name).string());
  a.outputs.RefuseInputs(inputs);
  // With a trajectory on standard output ("-"), everything else goes to stderr.
  std::ostream& info = a.outputs.UsesStdout() ? std::cerr : std::cout;
  if (a.outputs.csv.empty() && a.outputs.tum.empty() && a.outputs.kitti.empty() && a.plot.empty())
    std::cerr << "rgbdvo: warning: no --csv, --tum, --kitti or --plot: the trajectory is computed "
                 "but not written\n";
  const std::vector<std::unique_ptr<TrajectoryWriter>> writers = a.outputs.Open();
  std::vector<TrajectoryWriter*> writer_ptrs;
  writer_ptrs.reserve(writers.size() + 1);
  for (auto& w : writers) writer_ptrs.push_back(w.get());
  PoseRecorder recorder;
  if (!a.plot.empty()) writer_ptrs.push_back(&recorder);

  if (!a.quiet) {
    PrintConfiguration(info, source->Describe(), calib_path, calib, odometry_options, a.run);
    info << std::flush;
  }
  LimitOpenCvThreads();
  Odometry odometry(odometry_options, calib);
  const StopOnSignals stop_on_signals;
  StoppableSource stoppable(*source);
  StatusLine status(a.quiet, stoppable.Size());
  const RunSummary summary = RunOdometry(
      stoppable, odometry, writer_ptrs,
      [&](const FrameResult& r) {
        status.Update(r);
        DelayFrame(a.frame_delay_ms);
      },
      a.run, PrintWarning(status.redrawn()));
  status.Finish();
  info << summary.Brief() << std::endl;
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
    const std::string gt_path = (std::filesystem::path(a.folder) / "groundtruth.txt").string();
    std::vector<StampedPose> gt;
    if (std::filesystem::exists(gt_path)) gt = ReadTrajectory(gt_path).poses;
    PlotOptions plot;
    plot.title = "rgbdvo run " + a.folder;
    info << PlotTrajectory(recorder.poses, gt, a.plot, plot).Brief() << std::endl;
  }
  return 0;
}

}  // namespace

void AddRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run", "visual odometry over a recorded folder (TUM RGB-D or fakenect layout)");
  // Required unless --dump-config (checked by Run).
  cmd->add_option("folder", args->folder, "recording folder (required)");
  AddCalibFlag(cmd, &args->calib, "calibration YAML (required)");
  args->outputs.AddFlags(cmd);
  cmd->add_option("--depth-scale", args->source.tum.depth_units_per_m,
                  "TUM depth units per metre (default: the calibration's depth_units_per_m, else "
                  "5000)")
      ->capture_default_str()
      ->each([args](const std::string&) { args->depth_scale_given = true; });
  cmd->add_option("--max-dt", args->source.tum.max_time_diff_s, "max rgb-depth time difference, s")
      ->capture_default_str();
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
  AddThreadsFlag(cmd, &args->run);
  cmd->add_flag("--timing", args->timing, "also print milliseconds per frame for each stage");
  AddFrameDelayFlag(cmd, &args->frame_delay_ms);
  args->odometry_flags = std::make_unique<OdometryFlags>(cmd);
  cmd->callback([args] {
    const int code = Run(*args);
    if (code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace rgbdvo::cli
