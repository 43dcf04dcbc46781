// `rgbdvo synth-kinect FOLDER`: writes a synthetic Kinect v1 recording (fakenect layout) to try
// `rgbdvo capture` under fakenect and `rgbdvo run` without a device. Hidden (a developer aid).
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "rgbdvo/synthetic/synthetic_kinect.hpp"

namespace rgbdvo::cli {

void AddSynthKinectCommand(CLI::App& app) {
  struct Args {
    std::string folder;
    int frames = 30;
    uint32_t seed = 7;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "synth-kinect", "write a synthetic Kinect v1 recording (fakenect layout) for testing");
  cmd->group("");  // hidden from --help
  cmd->add_option("folder", args->folder, "new recording folder (must not exist or be empty)")
      ->required();
  cmd->add_option("--frames", args->frames, "number of frames (30 Hz)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "scene seed")->capture_default_str();
  cmd->callback([args] {
    const SyntheticKinectOptions options;
    WriteSyntheticKinectRecording(args->folder, SyntheticScene(args->seed), options,
                                  MakeKinectRangePath(args->frames));
    std::cout << "wrote " << args->frames << " frames to " << args->folder
              << " (calibration: calib.yaml, eq. 1 exact at 2.5 m, and calib_depth_aware.yaml;"
                 " IR camera ground truth: groundtruth.txt)"
              << std::endl;
  });
}

}  // namespace rgbdvo::cli
