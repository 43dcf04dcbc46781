// `rgbdvo synth-kinect FOLDER`: writes a synthetic Kinect v1 recording (fakenect layout) to try
// `rgbdvo capture` under fakenect and `rgbdvo run` without a device; with --robot, a ground
// robot's laps with depth noise and the floor's truth (robot.txt). Hidden (a developer aid).
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "rgbdvo/synthetic/robot_path.hpp"
#include "rgbdvo/synthetic/synthetic_kinect.hpp"

namespace rgbdvo::cli {

void AddSynthKinectCommand(CLI::App& app) {
  struct Args {
    std::string folder;
    int frames = 30;
    uint32_t seed = 7;
    bool robot = false;
    double start_m = 0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "synth-kinect", "write a synthetic Kinect v1 recording (fakenect layout) for testing");
  cmd->group("");  // hidden from --help
  cmd->add_option("folder", args->folder, "new recording folder (must not exist or be empty)")
      ->required();
  CLI::Option* frames = cmd->add_option("--frames", args->frames,
                                        "number of frames (30 Hz; with --robot, default one lap)")
                            ->check(CLI::Range(1, 100000))
                            ->capture_default_str();
  cmd->add_option("--seed", args->seed, "scene seed")->capture_default_str();
  CLI::Option* robot = cmd->add_flag(
      "--robot", args->robot,
      "a ground robot's laps of a 5 x 3.5 m rectangle in a hall, with depth noise and "
      "the floor's truth in robot.txt (about 1.5 MB per frame)");
  cmd->add_option("--start", args->start_m,
                  "with --robot: start this far along the lap, m (the feature-poor side begins "
                  "at 8 m)")
      ->capture_default_str()
      ->needs(robot);
  cmd->callback([args, frames] {
    if (args->robot) {
      RobotPathOptions path;
      path.start_m = args->start_m;
      const int n = frames->count() > 0 ? args->frames : path.LapFrames();
      WriteRobotRecording(args->folder, path, n, args->seed);
      std::cout << "wrote " << n << " frames (" << n / static_cast<double>(path.LapFrames())
                << " laps of " << path.LapLength() << " m) to " << args->folder
                << " (calibration: calib.yaml and calib_depth_aware.yaml; colour camera ground "
                   "truth: groundtruth.txt; the floor under the IR camera: robot.txt)"
                << std::endl;
      return;
    }
    const SyntheticKinectOptions options;
    WriteSyntheticKinectRecording(args->folder, SyntheticScene(args->seed), options,
                                  MakeKinectRangePath(args->frames));
    std::cout << "wrote " << args->frames << " frames to " << args->folder
              << " (calibration: calib.yaml, eq. 1 exact at 2.5 m, and calib_depth_aware.yaml;"
                 " colour camera ground truth: groundtruth.txt)"
              << std::endl;
  });
}

}  // namespace rgbdvo::cli
