#include "commands.hpp"

namespace rgbdvo::cli {

void AddOdometryFlags(CLI::App* cmd, OdometryOptions* o) {
  const std::string g = "Odometry (defaults: Fiala & Ufkes 2011)";
  cmd->add_option("--max-features", o->features.max_features, "SIFT: keep the N strongest, 0 = all")
      ->group(g)->capture_default_str();
  cmd->add_option("--contrast-threshold", o->features.contrast_threshold, "SIFT DoG contrast threshold")
      ->group(g)->capture_default_str();
  cmd->add_option("--ratio", o->matching.ratio, "Lowe ratio test: best < ratio * second best")
      ->group(g)->capture_default_str();
  cmd->add_flag("!--no-mutual", o->matching.mutual, "do not require mutual nearest neighbours")
      ->group(g);
  cmd->add_option("--trials", o->ransac.max_trials, "RANSAC hypotheses (paper: 200)")
      ->group(g)->capture_default_str();
  cmd->add_option("--sample-size", o->ransac.sample_size, "matches per RANSAC hypothesis (paper: 4)")
      ->group(g)->capture_default_str();
  cmd->add_option("--inlier-dist", o->ransac.inlier_distance_m, "RANSAC inlier 3D distance, m (paper: 0.015)")
      ->group(g)->capture_default_str();
  cmd->add_option("--min-inliers", o->verify.min_inliers, "reject a frame with fewer inliers (paper: 15)")
      ->group(g)->capture_default_str();
  cmd->add_option("--max-translation", o->verify.max_translation_m, "reject a larger motion per frame, m (paper: 0.5)")
      ->group(g)->capture_default_str();
  cmd->add_option("--max-rotation", o->verify.max_rotation_deg, "reject a larger rotation per frame, deg (paper: 60)")
      ->group(g)->capture_default_str();
  cmd->add_option("--max-rejected-run", o->max_rejected_run,
                  "after N rejected frames in a row restart from the current frame (0 = never)")
      ->group(g)->capture_default_str();
  cmd->add_option("--seed", o->seed, "RANSAC random seed")->group(g)->capture_default_str();
}

}  // namespace rgbdvo::cli
