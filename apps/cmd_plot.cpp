// `rgbdvo plot ESTIMATE [--gt GROUNDTRUTH] --png OUT`: top and side view of a trajectory.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "output_paths.hpp"
#include "rgbdvo/evaluation/plot.hpp"

namespace rgbdvo::cli {

void AddPlotCommand(CLI::App& app) {
  struct Args {
    std::string estimate, groundtruth, png;
    PlotOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "plot", "PNG of a trajectory (top and side view), with aligned ground truth if given");
  cmd->add_option("estimate", args->estimate, "trajectory (TUM or rgbdvo CSV)")->required();
  cmd->add_option("--gt", args->groundtruth, "ground truth trajectory, aligned and overlaid");
  cmd->add_option("--png", args->png, "output PNG")->required();
  cmd->add_option("--title", args->options.title,
                  "figure title (default: the estimate's file name)");
  cmd->add_option("--max-dt", args->options.max_dt_s, "time matching for the alignment, s")
      ->capture_default_str();
  cmd->callback([args] {
    RefuseOutputsOntoInputs({{args->png, "--png"}}, {args->estimate, args->groundtruth});
    PlotOptions options = args->options;
    if (options.title.empty()) options.title = args->estimate;
    const Trajectory estimate = ReadTrajectory(args->estimate);
    const std::vector<StampedPose> gt = args->groundtruth.empty()
                                            ? std::vector<StampedPose>{}
                                            : ReadTrajectory(args->groundtruth).poses;
    std::cout << PlotTrajectory(estimate.poses, gt, args->png, options).Brief() << std::endl;
  });
}

}  // namespace rgbdvo::cli
