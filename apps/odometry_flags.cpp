#include "odometry_flags.hpp"

namespace rgbdvo::cli {
namespace {
const char* kGroup = "Odometry (see docs/method.md; --preset paper = Fiala & Ufkes 2011 exactly)";
}

template <typename T>
void OdometryFlags::Add(const std::string& name, T& (*field)(OdometryOptions&),
                        const std::string& help) {
  const OdometryOptions defaults;
  CLI::Option* opt = cmd_->add_option(name, field(given_), help)->group(kGroup);
  opt->default_str(CLI::detail::to_string(field(const_cast<OdometryOptions&>(defaults))));
  apply_given_.push_back([this, opt, field](OdometryOptions& o) {
    if (opt->count() > 0) field(o) = field(given_);
  });
}

void OdometryFlags::AddSwitch(const std::string& name, bool& (*field)(OdometryOptions&), bool value,
                              const std::string& help) {
  CLI::Option* opt = cmd_->add_flag(name, help)->group(kGroup);
  apply_given_.push_back([opt, field, value](OdometryOptions& o) {
    if (opt->count() > 0) field(o) = value;
  });
}

OdometryFlags::OdometryFlags(CLI::App* cmd) : cmd_(cmd) {
  cmd->add_option("--preset", preset_, "default (most accurate) or paper (Fiala & Ufkes 2011)")
      ->group(kGroup)
      ->check(CLI::IsMember({"default", "paper"}))
      ->capture_default_str();
  using O = OdometryOptions;
  Add<std::string>(
      "--sift", [](O& o) -> std::string& { return o.features.implementation; },
      "SIFT implementation: rgbdvo (own, faster) or opencv (cv::SIFT)");
  Add<int>(
      "--max-features", [](O& o) -> int& { return o.features.max_features; },
      "SIFT: keep the N strongest, 0 = all");
  Add<double>(
      "--contrast-threshold", [](O& o) -> double& { return o.features.contrast_threshold; },
      "SIFT DoG contrast threshold");
  Add<int>(
      "--octave-layers", [](O& o) -> int& { return o.features.octave_layers; },
      "SIFT scales per octave");
  Add<bool>(
      "--sift-upsample", [](O& o) -> bool& { return o.features.upsample_first_octave; },
      "SIFT: 2x-upsampled first octave (Lowe, OpenCV) or, false, the image's own resolution");
  Add<double>(
      "--ratio", [](O& o) -> double& { return o.matching.ratio; },
      "Lowe ratio test: best < ratio * second best");
  AddSwitch(
      "--no-mutual", [](O& o) -> bool& { return o.matching.mutual; }, false,
      "do not require mutual nearest neighbours");
  AddSwitch(
      "--mutual", [](O& o) -> bool& { return o.matching.mutual; }, true,
      "require mutual nearest neighbours (default; not in --preset paper)");
  Add<double>(
      "--guided-radius", [](O& o) -> double& { return o.guided_radius_px; },
      "guided matching: search radius around the motion prior's prediction, px (0 = brute force)");
  Add<double>(
      "--depth-jump", [](O& o) -> double& { return o.lifting.max_depth_jump_ratio; },
      "bilinear depth, refused across jumps above this fraction (0 = nearest pixel)");
  Add<int>(
      "--trials", [](O& o) -> int& { return o.ransac.max_trials; },
      "RANSAC hypotheses (paper: 200)");
  Add<int>(
      "--sample-size", [](O& o) -> int& { return o.ransac.sample_size; },
      "matches per RANSAC hypothesis (paper: 4)");
  Add<double>(
      "--inlier-dist", [](O& o) -> double& { return o.ransac.inlier_distance_m; },
      "RANSAC inlier 3D distance, m (paper: 0.015)");
  Add<double>(
      "--ransac-confidence", [](O& o) -> double& { return o.ransac.confidence; },
      "stop RANSAC early at this confidence (0 = always --trials, the paper)");
  Add<int>(
      "--min-inliers", [](O& o) -> int& { return o.verify.min_inliers; },
      "reject a frame with fewer inliers (paper: 15)");
  Add<double>(
      "--max-translation", [](O& o) -> double& { return o.verify.max_translation_m; },
      "reject a larger motion per frame, m (paper: 0.5)");
  Add<double>(
      "--max-rotation", [](O& o) -> double& { return o.verify.max_rotation_deg; },
      "reject a larger rotation per frame, deg (paper: 60)");
  AddSwitch(
      "--no-refine", [](O& o) -> bool& { return o.refine_enabled; }, false,
      "skip the reprojection+depth refinement (the paper's SVD only)");
  Add<double>(
      "--pixel-sigma", [](O& o) -> double& { return o.refine.pixel_sigma; },
      "refinement: keypoint noise, px");
  Add<double>(
      "--depth-noise", [](O& o) -> double& { return o.refine.depth_noise_coeff; },
      "refinement: depth noise sigma_z = c*z^2, c in 1/m (Khoshelham & Elberink 2012)");
  Add<double>(
      "--inlier-sigmas", [](O& o) -> double& { return o.refine.inlier_sigmas; },
      "refinement: inlier below this whitened error");
  Add<double>(
      "--keyframe-ratio", [](O& o) -> double& { return o.keyframe_inlier_ratio; },
      "new keyframe when inliers < ratio * the keyframe's first inliers (0 = every frame)");
  AddSwitch(
      "--no-undistort", [](O& o) -> bool& { return o.undistort; }, false,
      "ignore the calibration's lens distortion (the paper's pinhole model)");
  Add<int>(
      "--max-rejected-run", [](O& o) -> int& { return o.max_rejected_run; },
      "after N rejected frames in a row restart from the current frame (0 = never)");
  AddSwitch(
      "--no-depth-fallback", [](O& o) -> bool& { return o.depth_fallback; }, false,
      "when features fail, report the prediction instead of aligning the depth images by ICP");
  AddSwitch(
      "--depth-fallback", [](O& o) -> bool& { return o.depth_fallback; }, true,
      "when features fail, align the depth images by ICP (default; not in --preset paper)");
  Add<int>(
      "--depth-term-step", [](O& o) -> int& { return o.depth_term_step; },
      "also align the depth surfaces at every N-th pixel in the refinement (e.g. 16; "
      "default 0 = features only)");
  AddSwitch(
      "--no-depth-delay", [](O& o) -> bool& { return o.compensate_depth_delay; }, false,
      "read depth at the keypoint's own pixel, not moved over the colour-depth time offset");
  AddSwitch(
      "--no-predict", [](O& o) -> bool& { return o.predict_failed_frames; }, false,
      "report a frame without an estimate at the last pose (the paper), not the prediction");
  Add<uint32_t>(
      "--seed", [](O& o) -> uint32_t& { return o.seed; }, "RANSAC random seed");
}

OdometryOptions OdometryFlags::Resolve() const {
  OdometryOptions o = PresetOptions(preset_);
  for (const auto& apply : apply_given_) apply(o);
  o.Check();
  return o;
}

}  // namespace rgbdvo::cli
