// `rgbdvo eval GROUNDTRUTH ESTIMATE`: ATE and RPE of a trajectory against ground truth.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "rgbdvo/evaluation/evaluation.hpp"

namespace rgbdvo::cli {

void AddEvalCommand(CLI::App& app) {
  struct Args {
    std::string groundtruth, estimate;
    EvaluationOptions options;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "eval", "ATE and RPE of a trajectory against ground truth (TUM benchmark definitions)");
  cmd->add_option("groundtruth", args->groundtruth, "ground truth trajectory (TUM or rgbdvo CSV)")
      ->required();
  cmd->add_option("estimate", args->estimate, "estimated trajectory (TUM or rgbdvo CSV)")
      ->required();
  cmd->add_option("--max-dt", args->options.max_dt_s, "ATE: largest time difference of a match, s")
      ->capture_default_str();
  cmd->add_option("--delta", args->options.delta_s, "RPE: time step between pose pairs, s")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object instead of the table");
  cmd->callback([args] {
    const EvaluationReport report = EvaluateFiles(args->groundtruth, args->estimate, args->options);
    std::cout << (args->json ? report.Json() : report.Table()) << std::flush;
  });
}

}  // namespace rgbdvo::cli
