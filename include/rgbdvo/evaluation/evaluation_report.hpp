#pragma once
// An evaluation of trajectory files against ground truth: ATE and RPE (evaluation.hpp) with the
// files' pose counts, as a table or JSON, for one estimate or several side by side.

#include <string>
#include <vector>

#include "rgbdvo/evaluation/evaluation.hpp"

namespace rgbdvo {

struct EvaluationReport {
  std::string groundtruth_path, estimate_path;
  int groundtruth_poses = 0, estimate_poses = 0;
  int groundtruth_repeated = 0, estimate_repeated = 0;  // rows with a repeated timestamp, dropped
  EvaluationOptions options;
  AteResult ate;
  RpeResult rpe;
  std::string Table() const;  // a short human-readable table
  std::string Json() const;   // one JSON object
};

// Reads both files and computes ATE and RPE (the RPE with the ATE's scale). Throws for
// unreadable files and when no estimate pose has a ground truth pose within max_dt (no
// overlapping timestamps).
EvaluationReport EvaluateFiles(const std::string& groundtruth_path,
                               const std::string& estimate_path, const EvaluationOptions& options);

// Several estimates against one ground truth: one row per estimate (ATE and RPE statistics),
// and a JSON array of EvaluationReport::Json objects.
std::string ComparisonTable(const std::vector<EvaluationReport>& reports);
std::string ComparisonJson(const std::vector<EvaluationReport>& reports);

}  // namespace rgbdvo
