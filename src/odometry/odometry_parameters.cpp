#include "rgbdvo/odometry/odometry_parameters.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/io/text.hpp"
#include "rgbdvo/util/display_text.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {
namespace {

using O = OdometryOptions;

// The enum's name for `value`.
template <typename E>
const char* NameOf(E value) {
  for (const auto& [e, name] : EnumNames<E>())
    if (e == value) return name;
  return "?";
}

// The list itself. A new parameter: a field in its options struct, then one line here.
const std::vector<OdometryParameter> kParameters = {
    {"features.implementation", "sift",
     "SIFT implementation: rgbdvo (own, faster) or opencv (cv::SIFT)",
     [](O& o) -> ParameterRef { return &o.features.implementation; }},
    {"features.max_features",
     "max-features",
     "SIFT: keep the N strongest, 0 = all",
     [](O& o) -> ParameterRef { return &o.features.max_features; },
     {0, 100000}},
    {"features.octave_layers",
     "octave-layers",
     "SIFT scales per octave",
     [](O& o) -> ParameterRef { return &o.features.octave_layers; },
     {1, 10}},
    {"features.contrast_threshold",
     "contrast-threshold",
     "SIFT DoG contrast threshold",
     [](O& o) -> ParameterRef { return &o.features.contrast_threshold; },
     {0, 1}},
    {"features.edge_threshold",
     "edge-threshold",
     "SIFT edge response ratio (Lowe: 10)",
     [](O& o) -> ParameterRef { return &o.features.edge_threshold; },
     {0, 1000}},
    {"features.sigma",
     "sift-sigma",
     "SIFT base blur (Lowe: 1.6)",
     [](O& o) -> ParameterRef { return &o.features.sigma; },
     {0, 10}},
    {"features.upsample_first_octave", "sift-upsample",
     "SIFT from a 2x-upsampled first octave (Lowe, OpenCV); --no-sift-upsample: from the image's "
     "own resolution, about 3x less CPU",
     [](O& o) -> ParameterRef { return &o.features.upsample_first_octave; }},
    {"matching.ratio",
     "ratio",
     "Lowe ratio test: best < ratio * second best",
     [](O& o) -> ParameterRef { return &o.matching.ratio; },
     {0, 1}},
    {"matching.mutual", "mutual", "require mutual nearest neighbours (not in --preset paper)",
     [](O& o) -> ParameterRef { return &o.matching.mutual; }},
    {"guided_radius_px",
     "guided-radius",
     "guided matching: search radius around the motion prior's prediction, px (0 = brute force)",
     [](O& o) -> ParameterRef { return &o.guided_radius_px; },
     {0, 1000}},
    {"guided_rematch", "guided-rematch",
     "guided matching: match again around the estimate when its inliers reach the outer half of "
     "the radius (the prior was off); brute force decides a weak estimate it does not reproduce",
     [](O& o) -> ParameterRef { return &o.guided_rematch; }},
    {"lifting.max_depth_jump_ratio",
     "depth-jump",
     "bilinear depth, refused across jumps above this fraction (0 = nearest pixel)",
     [](O& o) -> ParameterRef { return &o.lifting.max_depth_jump_ratio; },
     {0, 1}},
    {"ransac.max_trials",
     "trials",
     "RANSAC hypotheses (paper: 200)",
     [](O& o) -> ParameterRef { return &o.ransac.max_trials; },
     {1, 100000}},
    {"ransac.sample_size",
     "sample-size",
     "matches per RANSAC hypothesis (paper: 4)",
     [](O& o) -> ParameterRef { return &o.ransac.sample_size; },
     {3, 100}},
    {"ransac.inlier_distance_m",
     "inlier-dist",
     "RANSAC inlier 3D distance, m (paper: 0.015)",
     [](O& o) -> ParameterRef { return &o.ransac.inlier_distance_m; },
     {0, 1}},
    {"ransac.confidence",
     "ransac-confidence",
     "stop RANSAC early at this confidence (0 = always --trials, the paper)",
     [](O& o) -> ParameterRef { return &o.ransac.confidence; },
     {0, 1}},
    {"motion.model", "motion",
     "6dof (any motion) or planar (a camera on a robot driving on a flat floor: x, z and yaw)",
     [](O& o) -> ParameterRef { return &o.motion.model; }},
    {"motion.floor", "floor",
     "planar: the floor's normal from the first frame's depth (depth), its accelerometer reading "
     "(accelerometer) or --mount-pitch and --mount-roll (given)",
     [](O& o) -> ParameterRef { return &o.motion.floor; }},
    {"motion.mount_pitch_deg",
     "mount-pitch",
     "planar, --floor given: the camera's pitch against the floor, deg (+: looks down)",
     [](O& o) -> ParameterRef { return &o.motion.mount_pitch_deg; },
     {-90, 90}},
    {"motion.mount_roll_deg",
     "mount-roll",
     "planar, --floor given: the camera's roll against the floor, deg",
     [](O& o) -> ParameterRef { return &o.motion.mount_roll_deg; },
     {-90, 90}},
    {"gravity_correction", "gravity",
     "correct roll and pitch drift toward the accelerometer's gravity (TUM accelerometer.txt, "
     "fakenect a- entries, a live Kinect; not with --motion planar)",
     [](O& o) -> ParameterRef { return &o.gravity_correction; }},
    {"gravity.time_constant_s",
     "gravity-time-constant",
     "gravity: seconds for the pull toward the accelerometer to close 63 % of a tilt error",
     [](O& o) -> ParameterRef { return &o.gravity.time_constant_s; },
     {0, 3600}},
    {"gravity.magnitude_sigma_mps2",
     "gravity-sigma",
     "gravity: a reading's weight falls as exp(-((|a| - g) / sigma)^2 / 2), m/s^2",
     [](O& o) -> ParameterRef { return &o.gravity.magnitude_sigma_mps2; },
     {0, 100}},
    {"verify.min_inliers",
     "min-inliers",
     "reject a frame with fewer inliers (paper: 15)",
     [](O& o) -> ParameterRef { return &o.verify.min_inliers; },
     {0, 100000}},
    {"verify.max_translation_m",
     "max-translation",
     "reject a larger motion per frame, m (paper: 0.5)",
     [](O& o) -> ParameterRef { return &o.verify.max_translation_m; },
     {0, 100}},
    {"verify.max_rotation_deg",
     "max-rotation",
     "reject a larger rotation per frame, deg (paper: 60)",
     [](O& o) -> ParameterRef { return &o.verify.max_rotation_deg; },
     {0, 180}},
    {"refine_enabled", "refine",
     "refine the motion on reprojection and depth residuals (--no-refine: the paper's SVD only)",
     [](O& o) -> ParameterRef { return &o.refine_enabled; }},
    {"refine.pixel_sigma",
     "pixel-sigma",
     "refinement: keypoint noise, px",
     [](O& o) -> ParameterRef { return &o.refine.pixel_sigma; },
     {0, 100}},
    {"refine.depth_noise_coeff",
     "depth-noise",
     "refinement: depth noise sigma_z = c*z^2, c in 1/m (Khoshelham & Elberink 2012)",
     [](O& o) -> ParameterRef { return &o.refine.depth_noise_coeff; },
     {0, 1}},
    {"refine.huber_sigmas",
     "huber-sigmas",
     "refinement: Huber threshold, sigmas",
     [](O& o) -> ParameterRef { return &o.refine.huber_sigmas; },
     {0, 100}},
    {"refine.inlier_sigmas",
     "inlier-sigmas",
     "refinement: inlier below this whitened error",
     [](O& o) -> ParameterRef { return &o.refine.inlier_sigmas; },
     {0, 100}},
    {"refine.max_iterations",
     "refine-iterations",
     "refinement: Levenberg-Marquardt iterations",
     [](O& o) -> ParameterRef { return &o.refine.max_iterations; },
     {0, 1000}},
    {"refine.selection_rounds",
     "selection-rounds",
     "refinement: rounds of inlier selection and refinement until the selection repeats",
     [](O& o) -> ParameterRef { return &o.refine.selection_rounds; },
     {0, 100}},
    {"keyframe_inlier_ratio",
     "keyframe-ratio",
     "new keyframe when inliers < ratio * the keyframe's first inliers (0 = every frame)",
     [](O& o) -> ParameterRef { return &o.keyframe_inlier_ratio; },
     {0, 1}},
    {"fuse_keyframe_pose", "keyframe-fusion",
     "a new keyframe's pose also from the last frame, the two averaged by their inliers "
     "(--no-keyframe-fusion: from the old keyframe alone)",
     [](O& o) -> ParameterRef { return &o.fuse_keyframe_pose; }},
    {"track_between_keyframes", "track",
     "between keyframes, track the keyframe's keypoints (Lucas-Kanade) instead of running SIFT "
     "and matching on every frame (--no-track: SIFT on every frame, as the paper)",
     [](O& o) -> ParameterRef { return &o.track_between_keyframes; }},
    {"tracking.window_px",
     "track-window",
     "tracking: Lucas-Kanade window side, px",
     [](O& o) -> ParameterRef { return &o.tracking.window_px; },
     {3, 101}},
    {"tracking.warp", "track-warp",
     "tracking: refine each track with the keyframe's window warped by the predicted motion "
     "(off: OpenCV's shifted window alone)",
     [](O& o) -> ParameterRef { return &o.tracking.warp; }},
    {"tracking.warp_window_px",
     "track-warp-window",
     "tracking: the warped refinement's window side, px",
     [](O& o) -> ParameterRef { return &o.tracking.warp_window_px; },
     {3, 101}},
    {"tracking.warp_min_px",
     "track-warp-min",
     "tracking: refine only where the warp moves a window corner this far from a shift, px",
     [](O& o) -> ParameterRef { return &o.tracking.warp_min_px; },
     {0, 100}},
    {"tracking.warp_max_shift_px",
     "track-warp-max-shift",
     "tracking: the warped refinement moves a track at most this far, px",
     [](O& o) -> ParameterRef { return &o.tracking.warp_max_shift_px; },
     {0, 100}},
    {"tracking.levels",
     "track-levels",
     "tracking: pyramid levels above the image",
     [](O& o) -> ParameterRef { return &o.tracking.levels; },
     {0, 8}},
    {"tracking.max_points",
     "track-points",
     "tracking: keyframe keypoints tracked, at most",
     [](O& o) -> ParameterRef { return &o.tracking.max_points; },
     {1, 100000}},
    {"track_stale_noise_ratio",
     "track-stale-noise",
     "tracking: new keyframe when the tracks' pixel noise exceeds this times the least on the "
     "keyframe's tracked frames so far (0 = not)",
     [](O& o) -> ParameterRef { return &o.track_stale_noise_ratio; },
     {0, 100}},
    {"compensate_depth_delay", "depth-delay",
     "lift keypoints where the depth image saw them, moved over the colour-depth time offset "
     "(--no-depth-delay: at the keypoint's own pixel, the paper)",
     [](O& o) -> ParameterRef { return &o.compensate_depth_delay; }},
    {"undistort", "undistort",
     "use the calibration's lens distortion (--no-undistort: the paper's pinhole model)",
     [](O& o) -> ParameterRef { return &o.undistort; }},
    {"local_map.enabled", "local-map",
     "local map: bundle adjustment of each new keyframe with the keyframes sharing its points "
     "(experimental, off by default)",
     [](O& o) -> ParameterRef { return &o.local_map.enabled; }},
    {"local_map.window_keyframes",
     "map-window",
     "local map: keyframes adjusted together",
     [](O& o) -> ParameterRef { return &o.local_map.window_keyframes; },
     {2, 100}},
    {"local_map.max_keyframes",
     "map-keyframes",
     "local map: keyframes kept (memory bound)",
     [](O& o) -> ParameterRef { return &o.local_map.max_keyframes; },
     {2, 1000}},
    {"local_map.search_radius_px",
     "map-search-radius",
     "local map: a map point is looked for this close to where it projects, px",
     [](O& o) -> ParameterRef { return &o.local_map.search_radius_px; },
     {0, 100}},
    {"local_map.max_iterations",
     "map-iterations",
     "local map: Levenberg-Marquardt iterations at most per adjustment",
     [](O& o) -> ParameterRef { return &o.local_map.max_iterations; },
     {1, 1000}},
    {"max_rejected_run",
     "max-rejected-run",
     "after N rejected frames in a row restart from the current frame (0 = never)",
     [](O& o) -> ParameterRef { return &o.max_rejected_run; },
     {0, 1000000}},
    {"depth_fallback", "depth-fallback",
     "when features fail, align the depth images by ICP (--no-depth-fallback: report the "
     "prediction)",
     [](O& o) -> ParameterRef { return &o.depth_fallback; }},
    {"depth_keyframe", "depth-keyframe",
     "align a run of frames without a feature estimate with a depth keyframe while it holds "
     "(--no-depth-keyframe: each with the frame before)",
     [](O& o) -> ParameterRef { return &o.depth_keyframe; }},
    {"depth_term_step",
     "depth-term-step",
     "align the depth surfaces at every N-th pixel in the refinement where the features leave the "
     "translation uncertain (0 = features only)",
     [](O& o) -> ParameterRef { return &o.depth_term_step; },
     {0, 1000}},
    {"depth_term_translation_std_m",
     "depth-term-std",
     "the depth surfaces join a frame whose features alone leave the translation less certain "
     "than this, m (standard deviation along the least certain direction; 0 = every frame)",
     [](O& o) -> ParameterRef { return &o.depth_term_translation_std_m; },
     {0, 10}},
    {"predict_failed_frames", "predict",
     "report a frame without an estimate at the constant-velocity prediction (--no-predict: at "
     "the last pose, the paper)",
     [](O& o) -> ParameterRef { return &o.predict_failed_frames; }},
    {"seed",
     "seed",
     "RANSAC random seed",
     [](O& o) -> ParameterRef { return &o.seed; },
     {0, 4294967295.0}},
};

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

template <>
const std::vector<std::pair<SiftImplementation, const char*>>& EnumNames<SiftImplementation>() {
  static const std::vector<std::pair<SiftImplementation, const char*>> names = {
      {SiftImplementation::kRgbdvo, "rgbdvo"}, {SiftImplementation::kOpenCv, "opencv"}};
  return names;
}

template <>
const std::vector<std::pair<MotionModelKind, const char*>>& EnumNames<MotionModelKind>() {
  static const std::vector<std::pair<MotionModelKind, const char*>> names = {
      {MotionModelKind::kSixDof, "6dof"}, {MotionModelKind::kPlanar, "planar"}};
  return names;
}

template <>
const std::vector<std::pair<FloorSource, const char*>>& EnumNames<FloorSource>() {
  static const std::vector<std::pair<FloorSource, const char*>> names = {
      {FloorSource::kDepth, "depth"},
      {FloorSource::kAccelerometer, "accelerometer"},
      {FloorSource::kGiven, "given"}};
  return names;
}

std::string FormatParameter(ParameterRef field) {
  std::ostringstream s;
  s.precision(15);
  std::visit(
      [&](auto* value) {
        using T = std::remove_pointer_t<decltype(value)>;
        if constexpr (std::is_same_v<T, bool>)
          s << (*value ? "true" : "false");
        else if constexpr (std::is_enum_v<T>)
          s << NameOf(*value);
        else
          s << *value;
      },
      field);
  return s.str();
}

std::string FormatRange(const ParameterRange& range) {
  std::ostringstream s;
  s.precision(15);
  s << "[" << range.min << ", " << range.max << "]";
  return s.str();
}

void ParseParameter(const char* key, const std::string& text, ParameterRef field,
                    const ParameterRange& range) {
  const std::string value = Trim(text);
  const auto bad = [&](const std::string& what) {
    return std::invalid_argument(std::string(key) + ": '" + Excerpt(value) + "' is not " + what);
  };
  std::visit(
      [&](auto* target) {
        using T = std::remove_pointer_t<decltype(target)>;
        if constexpr (std::is_enum_v<T>) {
          std::string names;
          for (const auto& [e, name] : EnumNames<T>()) {
            if (value == name) {
              *target = e;
              return;
            }
            names += std::string(names.empty() ? "" : ", ") + name;
          }
          throw bad("one of " + names);
        } else if constexpr (std::is_same_v<T, bool>) {
          const std::string v = Lower(value);
          if (v == "true" || v == "1" || v == "yes" || v == "on")
            *target = true;
          else if (v == "false" || v == "0" || v == "no" || v == "off")
            *target = false;
          else
            throw bad("true or false");
        } else {
          double number;
          try {
            number = ParseNumber(value, key);
          } catch (const std::runtime_error&) {
            throw bad("a number");
          }
          if constexpr (!std::is_same_v<T, double>) {
            if (number != std::floor(number) || number < std::numeric_limits<T>::min() ||
                number > std::numeric_limits<T>::max())
              throw bad(std::is_same_v<T, int> ? "an integer" : "a non-negative integer");
          }
          if (!(number >= range.min && number <= range.max))
            throw bad("within " + FormatRange(range));
          *target = static_cast<T>(number);
        }
      },
      field);
}

const std::vector<OdometryParameter>& OdometryParameters() { return kParameters; }

const OdometryParameter* FindParameter(const std::string& key) {
  for (const OdometryParameter& p : kParameters)
    if (key == p.key) return &p;
  return nullptr;
}

namespace {

// Parameters that were removed, with the value they always had by default: a configuration file
// written before (--dump-config) still loads where it kept that value.
struct RetiredParameter {
  const char* key;
  const char* default_value;
  const char* why;
};
const RetiredParameter kRetired[] = {
    {"tracking.fusion", "false",
     "the keyframe fusion's tracks back were less accurate than SIFT there: "
     "docs/decisions/0039-track-fusion.md"},
    {"tracking.max_back_error_px", "0",
     "the forward-backward check dropped right tracks in motion blur: "
     "docs/decisions/0032-track-option.md"},
};

// Keys renamed to their field's path in OdometryOptions, still read under the old name.
const std::pair<const char*, const char*> kRenamed[] = {
    {"matching.guided_radius_px", "guided_radius_px"},
    {"matching.guided_rematch", "guided_rematch"},
    {"gravity.enabled", "gravity_correction"},
    {"refine.enabled", "refine_enabled"},
    {"tracking.enabled", "track_between_keyframes"},
    {"tracking.stale_noise_ratio", "track_stale_noise_ratio"},
};

// The key under its current name.
std::string CurrentKey(const std::string& key) {
  for (const auto& [old_key, new_key] : kRenamed)
    if (key == old_key) return new_key;
  return key;
}

// True for a retired key at its old default (the line is skipped); throws naming `where` for a
// retired key set to anything else.
bool RetiredAtItsDefault(const std::string& key, const std::string& value,
                         const std::string& where) {
  for (const RetiredParameter& r : kRetired) {
    if (key != r.key) continue;
    if (value == r.default_value) return true;
    throw std::runtime_error(where + ": parameter '" + Excerpt(key) + "' was removed (" + r.why +
                             "); delete the line");
  }
  return false;
}

}  // namespace

void ApplyConfig(
    std::istream& in, const std::string& name, OdometryOptions* options,
    const std::function<bool(const std::string& key, const std::string& value)>& other) {
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const std::string where = name + ":" + std::to_string(number);
    const std::string content = Trim(line.substr(0, line.find('#')));
    if (content.empty()) continue;
    const size_t eq = content.find('=');
    if (eq == std::string::npos)
      throw std::runtime_error(where + ": expected 'key = value', got '" + Excerpt(content) + "'");
    const std::string key = CurrentKey(Trim(content.substr(0, eq)));
    if (RetiredAtItsDefault(key, Trim(content.substr(eq + 1)), where)) continue;
    try {
      if (other && other(key, content.substr(eq + 1))) continue;
      const OdometryParameter* p = FindParameter(key);
      if (!p)
        throw std::runtime_error(where + ": unknown parameter '" + Excerpt(key) +
                                 "' (`rgbdvo run --dump-config` lists them)");
      p->Set(content.substr(eq + 1), options);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(where + ": " + e.what());
    }
  }
  if (in.bad()) throw std::runtime_error(name + ": read error");
}

void ApplyConfigFile(
    const std::string& path, OdometryOptions* options,
    const std::function<bool(const std::string& key, const std::string& value)>& other) {
  std::istringstream in(ReadTextFile(path, "configuration file", kMaxConfigFileBytes));
  ApplyConfig(in, path, options, other);
}

}  // namespace rgbdvo
