// `rgbdvo eval GROUNDTRUTH ESTIMATE [ESTIMATE ...]`: ATE and RPE of trajectories against ground
// truth.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "output_paths.hpp"
#include "rgbdvo/evaluation/evaluation_plots.hpp"
#include "rgbdvo/evaluation/evaluation_report.hpp"

namespace rgbdvo::cli {

void AddEvalCommand(CLI::App& app) {
  struct Args {
    std::string groundtruth;
    std::vector<std::string> estimates;
    EvaluationOptions options;
    std::string align = "se3", delta_unit = "s";
    bool json = false;
    EvaluationFigures figures;
    EvaluationPlotOptions plot;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "ATE and RPE of trajectories against ground truth (TUM benchmark definitions by default, "
      "evo's options)");
  cmd->add_option("groundtruth", args->groundtruth, "ground truth trajectory (TUM or rgbdvo CSV)")
      ->required();
  cmd->add_option("estimates", args->estimates,
                  "estimated trajectories (TUM or rgbdvo CSV): one row each")
      ->required();
  cmd->add_option("--max-dt", args->options.max_dt_s,
                  "largest time difference of a ground truth-estimate match, s")
      ->capture_default_str();
  cmd->add_option("--t-offset", args->options.t_offset_s,
                  "added to the estimates' timestamps before matching, s")
      ->capture_default_str();
  cmd->add_option("--align", args->align,
                  "ATE alignment: se3 (rigid, TUM), sim3 (rigid + scale), scale (scale only), "
                  "origin (first poses), none")
      ->check(CLI::IsMember({"se3", "sim3", "scale", "origin", "none"}))
      ->capture_default_str();
  cmd->add_option("--align-first", args->options.align_first,
                  "fit the alignment to the first N matched poses (0 = all)")
      ->capture_default_str();
  cmd->add_option("--delta", args->options.delta, "RPE: step between the poses of a pair")
      ->capture_default_str();
  cmd->add_option("--delta-unit", args->delta_unit,
                  "unit of --delta: s (TUM), frames (of the matched poses), m (ground truth path)")
      ->check(CLI::IsMember({"s", "frames", "m"}))
      ->capture_default_str();
  cmd->add_flag("--json", args->json,
                "print JSON instead of the table: one object, an array for several estimates");
  cmd->add_option("--plot", args->figures.trajectories,
                  "PNG: top and side view of the ground truth and every aligned estimate");
  cmd->add_option("--plot-errors", args->figures.errors,
                  "PNG: ATE of every matched pose over time, a line per estimate");
  cmd->add_option("--plot-xyz", args->figures.poses,
                  "PNG: x, y, z, roll, pitch, yaw over time, ground truth and aligned estimates");
  cmd->add_option("--title", args->plot.title, "title of the figures (default: evaluation)");
  cmd->callback([args] {
    std::vector<std::string> inputs = args->estimates;
    inputs.push_back(args->groundtruth);
    RefuseOutputsOntoInputs({{args->figures.trajectories, "--plot"},
                             {args->figures.errors, "--plot-errors"},
                             {args->figures.poses, "--plot-xyz"}},
                            inputs);
    EvaluationOptions options = args->options;
    options.align = ParseAlignment(args->align);
    options.delta_unit = ParseDeltaUnit(args->delta_unit);
    std::vector<EvaluationReport> reports;
    for (const std::string& estimate : args->estimates)
      reports.push_back(EvaluateFiles(args->groundtruth, estimate, options));
    if (reports.size() == 1)
      std::cout << (args->json ? reports[0].Json() : reports[0].Table());
    else
      std::cout << (args->json ? ComparisonJson(reports) : ComparisonTable(reports));
    // The figures after the table, on stderr with --json so that stdout stays one document.
    (args->json ? std::cerr : std::cout) << PlotEvaluation(reports, args->figures, args->plot);
    std::cout << std::flush;
  });
}

}  // namespace rgbdvo::cli
