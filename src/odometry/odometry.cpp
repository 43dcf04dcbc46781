#include "rgbdvo/odometry/odometry.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/estimation/depth_term.hpp"
#include "rgbdvo/estimation/floor_plane.hpp"
#include "rgbdvo/estimation/planar_motion.hpp"
#include "rgbdvo/geometry/motion_prior.hpp"
#include "rgbdvo/odometry/odometry_parameters.hpp"
#include "rgbdvo/odometry/point_pairs.hpp"
#include "rgbdvo/sensor/camera.hpp"
#include "rgbdvo/util/stopwatch.hpp"

namespace rgbdvo {

void OdometryOptions::Check() const {
  features.Check();
  matching.Check();
  lifting.Check();
  ransac.Check();
  verify.Check();
  refine.Check();
  if (!(keyframe_inlier_ratio >= 0 && keyframe_inlier_ratio <= 1))
    throw std::invalid_argument("OdometryOptions.keyframe_inlier_ratio must be in [0, 1]");
  if (!(guided_radius_px >= 0))
    throw std::invalid_argument("OdometryOptions.guided_radius_px must be >= 0");
  if (max_rejected_run < 0)
    throw std::invalid_argument("OdometryOptions.max_rejected_run must be >= 0");
  if (depth_term_step < 0)
    throw std::invalid_argument("OdometryOptions.depth_term_step must be >= 0");
  if (!(depth_term_translation_std_m >= 0))
    throw std::invalid_argument("OdometryOptions.depth_term_translation_std_m must be >= 0");
  if (motion != "6dof" && motion != "planar")
    throw std::invalid_argument("OdometryOptions.motion must be 6dof or planar, not '" + motion +
                                "'");
  if (floor != "depth" && floor != "accelerometer" && floor != "given")
    throw std::invalid_argument(
        "OdometryOptions.floor must be depth, accelerometer or given, not '" + floor + "'");
  gravity.Check();
  tracking.Check();
  if (!(track_stale_noise_ratio == 0 || track_stale_noise_ratio >= 1))
    throw std::invalid_argument(
        "OdometryOptions.track_stale_noise_ratio must be >= 1 (or 0 = no such keyframes)");
  if (gravity_correction && motion == "planar")
    throw std::invalid_argument(
        "OdometryOptions.gravity_correction corrects roll and pitch, which motion planar holds "
        "fixed: use one or the other");
  if (!(std::abs(mount_pitch_deg) < 90 && std::abs(mount_roll_deg) < 90))
    throw std::invalid_argument(
        "OdometryOptions.mount_pitch_deg and mount_roll_deg must be within (-90, 90)");
}

OdometryOptions PresetOptions(const std::string& name) {
  OdometryOptions o;
  if (name == "default") return o;
  if (name == "paper") {
    o.features = FeatureOptions::Lowe();   // Lowe's SIFT, as cv::SIFT's defaults
    o.features.implementation = "opencv";  // a reference SIFT (the paper names none)
    o.matching.mutual = false;             // the paper names no matching rule; a plain ratio test
    o.refine_enabled = false;              // SVD on the inliers only (eq. 5-10)
    o.keyframe_inlier_ratio = 0;           // successive frames
    o.fuse_keyframe_pose = false;          // one estimate per frame
    o.ransac.confidence = 0;               // always 200 trials
    o.undistort = false;                   // "a perfect pinhole model was used"
    o.lifting.max_depth_jump_ratio = 0;    // depth at the nearest pixel
    o.guided_radius_px = 0;                // brute-force matching
    o.guided_rematch = false;              // (no prior to correct)
    o.predict_failed_frames = false;       // a rejected frame keeps the last pose
    o.depth_fallback = false;              // features only
    o.depth_keyframe = false;              // (with the fallback) frame to frame
    o.compensate_depth_delay = false;      // depth at the keypoint's own pixel
    o.depth_term_step = 0;                 // feature residuals only
    o.track_between_keyframes = false;     // SIFT and matching on every frame
    return o;
  }
  throw std::invalid_argument("unknown preset '" + name + "' (expected default or paper)");
}

std::string OdometryOptions::ToString() const {
  std::string s;
  for (const OdometryParameter& p : OdometryParameters())
    s += std::string(p.key) + " = " + p.Get(*this) + "\n";
  return s;
}

bool HasFeatureEstimate(FrameStatus status) {
  return status == FrameStatus::kFirst || status == FrameStatus::kAccepted ||
         status == FrameStatus::kRecovered;
}

bool HasEstimate(FrameStatus status) {
  return HasFeatureEstimate(status) || status == FrameStatus::kDepth;
}

std::string FrameResult::StatusString() const {
  switch (status) {
    case FrameStatus::kFirst:
      return "first";
    case FrameStatus::kAccepted:
      return "accepted";
    case FrameStatus::kRecovered:
      return "recovered";
    case FrameStatus::kDepth:
      return "icp:" + reason;
    case FrameStatus::kPredicted:
      return "predicted:" + reason;
    case FrameStatus::kRejected:
      return "rejected:" + reason;
    case FrameStatus::kLost:
      return "lost:" + reason;
  }
  return "unknown";
}

Odometry::Odometry(const OdometryOptions& options, const Calibration& calib)
    : options_(options), calib_(calib), extractor_(options.features), rng_(options.seed) {
  options_.Check();
  calib_.Check();
  if (!options_.undistort) calib_.dist_ir = {0, 0, 0, 0, 0};
  if (options_.depth_fallback) {
    DepthAlignOptions d;
    d.max_translation_m = options_.verify.max_translation_m;
    d.max_rotation_deg = options_.verify.max_rotation_deg;
    d.depth_noise_coeff = options_.refine.depth_noise_coeff;
    depth_aligner_ = std::make_unique<DepthAligner>(d, calib_);
  }
  if (options_.gravity_correction) gravity_.emplace(options_.gravity);
}

FrameResult Odometry::Process(Frame frame) {
  if (ExtractsLazily()) return InColorCamera(Track(std::move(frame), std::nullopt));
  const Stopwatch t0;
  Features features = extractor_.Extract(frame.bgr);
  const double seconds = t0.Seconds();
  FrameResult r = Process(std::move(frame), std::move(features));
  r.times.features = seconds;
  return r;
}

MotionEstimate Odometry::EstimateFromMatches(const Reference& ref, const Reference& cur,
                                             const KeypointPoints& cur_points,
                                             const std::vector<cv::DMatch>& matches, FrameResult* r,
                                             std::vector<int>* match_of_pair) {
  r->matches = static_cast<int>(matches.size());
  Stopwatch t0;
  const std::vector<PointPair> pairs = PairMatches(ref.points, cur_points, matches, match_of_pair);
  r->times.lifting += t0.Seconds();
  r->pairs = static_cast<int>(pairs.size());

  t0.Restart();
  MotionEstimate estimate = MotionEstimate::FromRansac(
      level_from_cam_ ? EstimatePlanarRansac(options_.ransac, *level_from_cam_, pairs, rng_)
                      : EstimateRigidRansac(options_.ransac, pairs, rng_));
  if (estimate.success && options_.refine_enabled) {
    // Refine on the RANSAC inliers, measure the frame's noise scale there, then select inliers
    // by whitened error at that scale and refine on them until the selection settles.
    const double f = 0.5 * (calib_.fx + calib_.fy);
    const RansacResult& ransac = estimate.ransac;
    const Rigid3d T =
        RefineMotion(options_.refine, f, pairs, ransac.inliers, ransac.prev_from_cur).prev_from_cur;
    const NoiseScale noise = EstimateNoiseScale(options_.refine, f, pairs, ransac.inliers, T);
    estimate.pixel_noise = noise.pixel;
    const RefineOptions scaled = ScaleNoise(options_.refine, noise);
    std::optional<DepthPlaneTerm> dense;
    const auto add_depth_term = [&](const Rigid3d& at) {
      dense.emplace(calib_, depth_rays_, ref.depth_m, ref.depth_from_cam, cur.depth_points,
                    options_.refine.depth_noise_coeff, options_.lifting.max_depth_jump_ratio);
      // The features' pixel scale measures the frame's motion blur and rolling shutter; the
      // depth camera saw the same motion, so its surfaces are trusted no better.
      dense->ScaleNoise(std::max(EstimateDepthTermScale(*dense, at), noise.pixel));
    };
    const bool depth_term =
        options_.depth_term_step > 0 && !ref.depth_m.empty() && !cur.depth_points.empty();
    if (depth_term && options_.depth_term_translation_std_m == 0) add_depth_term(T);
    SelectionRefinement selected =
        RefineWithInlierSelection(scaled, f, pairs, T, dense ? &*dense : nullptr);
    if (depth_term && !dense && selected.refine &&
        !(TranslationStd(options_.refine, f, pairs, selected.inliers,
                         selected.refine->prev_from_cur) <=
          options_.depth_term_translation_std_m)) {
      // The features leave the translation uncertain: the depth surfaces join, from the
      // features' motion.
      const Rigid3d from = selected.refine->prev_from_cur;
      add_depth_term(from);
      selected = RefineWithInlierSelection(scaled, f, pairs, from, &*dense);
    }
    if (selected.refine) {
      estimate.refine = selected.refine;
      estimate.prev_from_cur = estimate.refine->prev_from_cur;
      if (scaled.planar_level_from_cam) {
        RefineOptions free = scaled;
        free.planar_level_from_cam.reset();
        estimate.unconstrained = RefineMotion(free, f, pairs, selected.inliers,
                                              estimate.prev_from_cur, dense ? &*dense : nullptr)
                                     .prev_from_cur;
      }
      estimate.inliers = std::move(selected.inliers);
    }
  }
  r->times.ransac += t0.Seconds();
  r->inliers = static_cast<int>(estimate.inliers.size());
  return estimate;
}

namespace {

// For each inlier of `motion`: the distance from the predicted position of its reference keypoint
// to the current keypoint it was matched with, colour pixels.
std::vector<float> PredictionErrors(const std::vector<std::optional<Eigen::Vector2d>>& predicted,
                                    const std::vector<cv::DMatch>& matches,
                                    const std::vector<int>& match_of_pair,
                                    const MotionEstimate& motion, const Features& cur) {
  std::vector<float> errors;
  errors.reserve(motion.inliers.size());
  for (int k : motion.inliers) {
    const cv::DMatch& m = matches[match_of_pair[k]];
    if (!predicted[m.queryIdx]) continue;
    const cv::Point2f& pt = cur.keypoints[m.trainIdx].pt;
    errors.push_back(
        static_cast<float>((*predicted[m.queryIdx] - Eigen::Vector2d(pt.x, pt.y)).norm()));
  }
  return errors;
}

// True when `image` is the only header of its buffer (allocated by OpenCV, continuous): kept, it
// cannot change under the odometry. A buffer someone else still refers to may be written again
// (a caller reading the next frame into the same cv::Mat): that one is copied.
bool SoleOwner(const cv::Mat& image) {
  return image.u != nullptr && image.u->refcount == 1 && image.isContinuous();
}

// The value below which a fraction q of `values` lie (nearest rank); 0 for none.
float Percentile(std::vector<float> values, double q) {
  if (values.empty()) return 0;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(q * (values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

}  // namespace

MotionEstimate Odometry::Estimate(const Reference& ref, const Reference& cur,
                                  const Rigid3d& world_from_cur_pred, FrameResult* r,
                                  std::string* reason) {
  Stopwatch t0;
  const Rigid3d cur_from_ref = world_from_cur_pred.inverse() * ref.world_from_cam;
  const std::vector<std::optional<Eigen::Vector2d>> predicted =
      PredictKeypoints(calib_, ref.points, cur_from_ref);
  const bool guided = options_.guided_radius_px > 0;
  GuidedMatchOptions g;
  g.radius_px = options_.guided_radius_px;
  g.ratio = options_.matching.ratio;
  g.mutual = options_.matching.mutual;
  std::vector<cv::DMatch> matches =
      guided ? MatchGuided(g, ref.features, predicted, cur.features)
             : MatchFeatures(options_.matching, ref.features, cur.features);
  r->times.matching += t0.Seconds();
  std::vector<int> match_of_pair;
  MotionEstimate motion = EstimateFromMatches(ref, cur, cur.points, matches, r, &match_of_pair);
  *reason = CheckMotion(options_.verify, motion);
  // Brute-force matching, timed and counted as a fallback.
  const auto match_all = [&] {
    ++r->fallbacks;
    const Stopwatch t;
    std::vector<cv::DMatch> all = MatchFeatures(options_.matching, ref.features, cur.features);
    r->times.matching += t.Seconds();
    return all;
  };
  bool brute_forced = !guided;
  if (!brute_forced && !reason->empty()) {
    // The prior was wrong (or the guided matches too few): brute force, as without it.
    brute_forced = true;
    matches = match_all();
    motion = EstimateFromMatches(ref, cur, cur.points, matches, r, &match_of_pair);
    *reason = CheckMotion(options_.verify, motion);
  }
  r->prediction_error_px =
      PredictionErrors(predicted, matches, match_of_pair, motion, cur.features);
  // The estimate from `other` replaces `motion` if it passes verification with at least `factor`
  // times its inliers; r's counts are the kept estimate's. Returns the other estimate's inliers
  // (0 when it fails verification).
  const auto replace_if_verified = [&](const std::vector<cv::DMatch>& other, size_t factor) {
    const int kept_matches = r->matches, kept_pairs = r->pairs, kept_inliers = r->inliers;
    std::vector<int> other_of_pair;
    MotionEstimate estimate = EstimateFromMatches(ref, cur, cur.points, other, r, &other_of_pair);
    const bool verified = CheckMotion(options_.verify, estimate).empty();
    const int inliers = verified ? r->inliers : 0;
    if (verified && estimate.inliers.size() >= factor * motion.inliers.size()) {
      r->prediction_error_px =
          PredictionErrors(predicted, other, other_of_pair, estimate, cur.features);
      motion = std::move(estimate);
    } else {
      r->matches = kept_matches, r->pairs = kept_pairs, r->inliers = kept_inliers;
    }
    return inliers;
  };
  if (guided && options_.guided_rematch && reason->empty() &&
      Percentile(r->prediction_error_px, 0.99) > 0.5 * options_.guided_radius_px) {
    // The inliers reach into the outer half of the radius (or beyond it, after brute force):
    // the prior was off by about as much as the radius, so right matches lay beyond it, and an
    // estimate from those within it can be biased (fr1/xyz every 5th frame, where the motion
    // reverses within a step: 27 inliers, 22 mm off). Around the estimate they lie within a few
    // pixels: match again there, guided (the ratio test among near candidates only), and keep
    // the second estimate if it verifies with at least as many inliers. (Where the prior was
    // right and blur spread the inliers, it finds no more: fr1_desk_fast90, 37 frames, a mean
    // of -1 inlier; fr1/xyz every 5th, where it was off, +94.)
    ++r->rematches;
    t0.Restart();
    const std::vector<cv::DMatch> again = MatchGuided(
        g, ref.features, PredictKeypoints(calib_, ref.points, motion.prev_from_cur.inverse()),
        cur.features);
    r->times.matching += t0.Seconds();
    const int first_inliers = r->inliers;
    const int again_inliers = replace_if_verified(again, 1);
    // Matched around itself the estimate finds fewer inliers than it has (so it was kept), and
    // it has few: it may be a wrong motion that a handful of wrong matches within the prior's
    // window agree on. Brute force decides; its estimate replaces the first only with at least
    // twice the inliers. (A reversed replay of fr1/xyz, one frame in 3, at a turn of the
    // motion: 16 inliers 4.8 degrees off, 9 around them, 292 by brute force. On the blurred
    // fast turn, where a few inliers are all the right motion leaves, brute force finds fewer.)
    if (!brute_forced && again_inliers < first_inliers &&
        first_inliers < 2 * options_.verify.min_inliers)
      replace_if_verified(match_all(), 2);
  }
  return motion;
}

void Odometry::EnsureFeatures(Reference* ref, FrameResult* r, Reference* beside) {
  // With a second thread, beside's SIFT runs on it while ref's runs here (Extract is const and
  // reentrant: the feature workers share it); its time counts as the stage's all the same.
  const bool side_by_side = beside && threads_ >= 2 && !ref->has_features && !beside->has_features;
  std::future<double> beside_seconds;
  if (side_by_side)
    beside_seconds = std::async(std::launch::async, [this, beside] {
      const Stopwatch t;
      beside->features = extractor_.Extract(beside->grey);
      return t.Seconds();
    });
  for (Reference* x : {ref, beside}) {
    if (!x || x->has_features) continue;
    Stopwatch t0;
    if (x == beside && side_by_side) {
      r->times.features += beside_seconds.get();
    } else {
      x->features = extractor_.Extract(x->grey);
      r->times.features += t0.Seconds();
    }
    ++r->sift_runs;
    t0.Restart();
    x->points = LiftKeypointsAcrossTime(calib_, options_.lifting, x->depth_m, x->features,
                                        x->depth_from_cam);
    x->has_features = true;
    r->times.lifting += t0.Seconds();
  }
}

MotionEstimate Odometry::EstimateTracked(const Reference& cur, const Rigid3d& world_from_cur_pred,
                                         FrameResult* r) {
  if (key_.tracked.empty()) {
    std::vector<bool> usable(key_.points.size());
    for (size_t i = 0; i < usable.size(); ++i) usable[i] = key_.points[i].has_value();
    key_.tracked = SelectSpread(key_.features.keypoints, usable, key_.grey.size(),
                                options_.tracking.max_points);
  }
  return EstimateFromTracks(&key_, key_.tracked, cur,
                            world_from_cur_pred.inverse() * key_.world_from_cam, r);
}

MotionEstimate Odometry::EstimateFromTracks(Reference* ref, const std::vector<int>& tracked,
                                            const Reference& cur, const Rigid3d& cur_from_ref_pred,
                                            FrameResult* r) {
  Stopwatch t0;
  // The reference is tracked from: its pyramid gets the derivatives once.
  if (!HasDerivatives(ref->pyramid))
    ref->pyramid = MakeTrackingPyramid(options_.tracking, ref->grey, /*with_derivatives=*/true);
  // Each tracked keypoint starts where the motion prior puts it (where it was, without a
  // prediction).
  KeypointPoints ref_points;
  std::vector<cv::Point2f> from, guess;
  for (int i : tracked) {
    ref_points.push_back(ref->points[i]);
    from.push_back(ref->features.keypoints[i].pt);
  }
  const std::vector<std::optional<Eigen::Vector2d>> predicted =
      PredictKeypoints(calib_, ref_points, cur_from_ref_pred);
  for (size_t k = 0; k < from.size(); ++k)
    guess.push_back(predicted[k] ? cv::Point2f(static_cast<float>(predicted[k]->x()),
                                               static_cast<float>(predicted[k]->y()))
                                 : from[k]);
  // The keyframe's windows are made at the first frame that tracks these points from it.
  const bool windows_kept = !ref->windows.from.empty() && ref->windows.points == from &&
                            ref->windows.from[0].data == ref->pyramid[0].data;
  if (!windows_kept) ref->windows = MakeTrackingWindows(options_.tracking, ref->pyramid, from);
  std::vector<std::optional<cv::Point2f>> landed =
      TrackPoints(options_.tracking, ref->windows, cur.pyramid, guess);
  if (options_.tracking.warp)
    RefineWarped(options_.tracking, ref->grey, cur.grey, from,
                 PredictWarps(calib_, ref_points, cur_from_ref_pred), &landed);
  // The tracks as matches: the reference's keypoint (queryIdx) and where it landed (trainIdx, a
  // keypoint of the reference's size there).
  Features moved;
  std::vector<cv::DMatch> matches;
  std::vector<size_t> track_of_match;
  for (size_t k = 0; k < landed.size(); ++k) {
    if (!landed[k]) continue;
    cv::KeyPoint kp = ref->features.keypoints[tracked[k]];
    kp.pt = *landed[k];
    matches.emplace_back(tracked[k], static_cast<int>(moved.keypoints.size()), 0.0f);
    moved.keypoints.push_back(kp);
    track_of_match.push_back(k);
  }
  r->times.matching += t0.Seconds();
  r->features = static_cast<int>(moved.size());
  t0.Restart();
  const KeypointPoints cur_points =
      LiftKeypointsAcrossTime(calib_, options_.lifting, cur.depth_m, moved, cur.depth_from_cam);
  r->times.lifting += t0.Seconds();
  std::vector<int> match_of_pair;
  MotionEstimate motion = EstimateFromMatches(*ref, cur, cur_points, matches, r, &match_of_pair);
  r->prediction_error_px.clear();
  for (int p : motion.inliers) {
    const size_t k = track_of_match[match_of_pair[p]];
    if (predicted[k])
      r->prediction_error_px.push_back(static_cast<float>(
          (*predicted[k] - Eigen::Vector2d((*landed[k]).x, (*landed[k]).y)).norm()));
  }
  return motion;
}

FrameResult Odometry::Process(Frame frame, Features features) {
  return InColorCamera(Track(std::move(frame), std::move(features)));
}

FrameResult Odometry::InColorCamera(FrameResult r) const {
  // ir_from_color = (I, c): colour0_from_colourk = ir_from_color^-1 * ir0_from_irk * ir_from_color.
  const Eigen::Vector3d c = ColorCenterInIr(calib_);
  if (c.isZero()) return r;
  Rigid3d ir_from_color = Rigid3d::Identity();
  ir_from_color.translation() = c;
  const Rigid3d color_from_ir = ir_from_color.inverse();
  r.world_from_cam = color_from_ir * r.world_from_cam * ir_from_color;
  if (r.world_from_cam_6dof)
    r.world_from_cam_6dof = color_from_ir * *r.world_from_cam_6dof * ir_from_color;
  // A turn moves the colour camera's centre too: v + w x c.
  r.velocity.translation_per_s += r.velocity.rotation_per_s.cross(c);
  return r;
}

FrameResult Odometry::Track(Frame frame, std::optional<Features> features) {
  FrameResult r;
  r.frame = frame.index;
  // The pose is the camera's at the colour image's time: the keypoints are seen then, and their
  // points are lifted into that camera (below). Colour times are also distinct, where two colour
  // frames can share one depth frame and its time.
  r.timestamp = frame.color_timestamp;
  r.depth_timestamp = frame.timestamp;
  r.features = features ? static_cast<int>(features->size()) : 0;

  // The motion prior: constant velocity from the last two accepted frames (none yet: zero),
  // timed by the colour images, where the keypoints are seen. (The depth images' times are
  // irregular: two colour frames can share one depth frame. Measured on fr1/xyz with brute-force
  // matching, prediction error of the final inliers at the 99th percentile / max: 8.5 / 16.0 px
  // with the colour times, 9.1 / 19.8 px with the depth times.)
  const bool moving = has_before_ && last_.color_timestamp > before_color_time_;
  const Rigid3d world_from_cur_pred =
      moving ? PredictConstantVelocity(world_from_before_, before_color_time_, last_.world_from_cam,
                                       last_.color_timestamp, frame.color_timestamp)
             : last_.world_from_cam;
  // The camera's motion from the colour image's time to the depth image's, at that velocity,
  // when the offset is within the interval the velocity was measured over (beyond it, the
  // timestamps are not to be trusted for extrapolation).
  Rigid3d depth_from_color = Rigid3d::Identity();
  const double depth_delay = frame.timestamp - frame.color_timestamp;
  if (moving && options_.compensate_depth_delay) {
    const double span = last_.color_timestamp - before_color_time_;
    if (std::abs(depth_delay) <= span)
      depth_from_color =
          ScaleMotion(world_from_before_.inverse() * last_.world_from_cam, depth_delay / span)
              .inverse();
  }

  const Stopwatch t0;
  Reference cur;
  if (features) {
    cur.points = LiftKeypointsAcrossTime(calib_, options_.lifting, frame.depth_m, *features,
                                         depth_from_color);
    cur.features = std::move(*features);
  } else {
    cur.has_features = false;
  }
  cur.frame = frame.index;
  cur.color_timestamp = frame.color_timestamp;
  if (options_.depth_fallback || options_.depth_term_step > 0 || options_.track_between_keyframes)
    cur.depth_m = SoleOwner(frame.depth_m) ? frame.depth_m : frame.depth_m.clone();
  cur.depth_from_cam = depth_from_color;
  if (options_.depth_term_step > 0) {
    if (depth_rays_.size() != frame.depth_m.size())
      depth_rays_ = DepthRays(calib_, frame.depth_m.size());
    cur.depth_points = SampleDepthPoints(depth_rays_, frame.depth_m, depth_from_color.inverse(),
                                         options_.depth_term_step);
  }
  r.times.lifting += t0.Seconds();
  if (options_.track_between_keyframes) {
    // What SIFT needs later, and the pyramid to track into, without derivatives until the frame
    // is tracked from (timed with matching, which the tracking replaces).
    const Stopwatch t1;
    cur.grey = GreyImage(frame.bgr);
    cur.pyramid = MakeTrackingPyramid(options_.tracking, cur.grey, /*with_derivatives=*/false);
    r.times.matching += t1.Seconds();
  }

  // A frame with fewer points than a verified motion needs inliers (no depth yet, as in the first
  // frames of a Kinect stream, a blank wall, a covered lens) cannot be matched by the frames
  // after it: it never becomes the reference.
  // SIFT on the current frame where it was not run yet; the frame's count is then its keypoints.
  const auto ensure_cur_features = [&] {
    EnsureFeatures(&cur, &r);
    r.features = static_cast<int>(cur.features.size());
  };
  const auto can_be_reference = [&] {
    ensure_cur_features();
    return std::count_if(cur.points.begin(), cur.points.end(), [](const auto& p) {
             return p.has_value();
           }) >= options_.verify.min_inliers;
  };
  // The first reference may also be a frame without such points whose depth image the depth
  // fallback can align the next frames with (a dark first colour image): readings on at least
  // half of it, the majority DepthAligner needs to agree.
  const auto depth_to_align = [&] {
    if (!options_.depth_fallback || frame.depth_m.empty()) return false;
    const cv::Mat readings = (frame.depth_m >= calib_.min_depth_m) &
                             (frame.depth_m <= calib_.max_depth_m) & (frame.depth_m > 0);
    return 2 * static_cast<size_t>(cv::countNonZero(readings)) >= frame.depth_m.total();
  };
  if (!started_ && !can_be_reference() && !depth_to_align()) {
    // No reference yet: reported at the origin, where the first reference will be; the next
    // frame is tried.
    r.reason = "reference_points<" + std::to_string(options_.verify.min_inliers);
    r.status = options_.predict_failed_frames ? FrameStatus::kPredicted : FrameStatus::kRejected;
    return r;
  }
  if (!started_) {
    SetUpMotionModel(frame);
    started_ = true;
    key_ = last_ = cur;
    has_before_ = false;
    CorrectTilt(frame);
    r.status = FrameStatus::kFirst;
    r.keyframe = true;
    return r;
  }

  // Tracked from the keyframe first (track_between_keyframes); where that fails verification,
  // SIFT matching as without tracking, for this frame and the keyframe's next ones (its tracks
  // no longer carry the motion; tracks_lost, below).
  MotionEstimate motion;
  bool tracked = false, track_failed = false;
  if (options_.track_between_keyframes && key_.has_features && !key_.tracks_lost) {
    motion = EstimateTracked(cur, world_from_cur_pred, &r);
    tracked = CheckMotion(options_.verify, motion).empty();
    track_failed = !tracked;
    r.from_tracks = tracked;
  }
  bool recovered = false;
  if (!tracked) {
    ensure_cur_features();
    motion = Estimate(key_, cur, world_from_cur_pred, &r, &r.reason);
  }
  if (!tracked && !r.reason.empty() && last_.frame != key_.frame) {
    // The keyframe is out of reach: try the last accepted frame, which then becomes the keyframe.
    EnsureFeatures(&last_, &r);
    std::string reason;
    MotionEstimate fallback = Estimate(last_, cur, world_from_cur_pred, &r, &reason);
    if (reason.empty()) {
      key_ = last_;
      motion = std::move(fallback);
      r.reason.clear();
      recovered = true;
    }
  }

  if (r.reason.empty()) {
    if (key_.first_inliers < 0) key_.first_inliers = r.inliers;
    // Tracks lost where SIFT still reaches the keyframe (a feature-poor view, a blurred frame):
    // the keyframe stays and its next frames are matched by SIFT, as without tracking, until
    // the usual rule renews it. Renewing at every such frame would chain the poses frame to
    // frame where the matches are fewest (synthetic robot lap, frames 820-900, a view of few
    // features: 19 mm of drift against the default's 4; docs/benchmarks.md).
    if (track_failed && !recovered) key_.tracks_lost = true;
    bool new_keyframe = (track_failed && recovered) ||
                        !(r.inliers >= options_.keyframe_inlier_ratio * key_.first_inliers &&
                          options_.keyframe_inlier_ratio > 0);
    if (tracked && options_.track_stale_noise_ratio > 0) {
      // The tracks' pixel noise grows as they go stale (fr1/xyz every 2nd frame, seed 42, by the
      // keyframe's age 1 / 2 / 3 / 4 / 5 / 6+ frames: 1.08 / 1.13 / 1.18 / 1.30 / 1.66 / 2.28;
      // docs/benchmarks.md). A frame's blur raises it too, without the tracks being stale: in
      // a fast turn it jumps from frame to frame (fr1/desk, frames 73-78: 1.0, 3.2, 1.0, 1.7,
      // 1.0, 1.3). The default ratio, 1.5, sits at the staleness curve's knee (between ages 4
      // and 5); at 1.2 the turn's milder blurred frames renewed the keyframe too (SIFT on 55 of
      // fast90's 90 frames against 47, equally accurate). The bar is the least noise measured
      // on the keyframe's tracked frames so far, not its first's: a blurred first tracked frame
      // would raise it for the keyframe's whole life (fr1/xyz every 3rd, seed 9: a first frame
      // at 1.50 and 1.00 on the next let 1.69 pass, and the keyframe after it tracked its frames
      // at 52-73 inliers and noise 2.0-2.2; ATE 0.0156 -> 0.0119 m; docs/benchmarks.md).
      if (!key_.staleness) key_.staleness.emplace(options_.track_stale_noise_ratio);
      if (key_.staleness->Stale(motion.pixel_noise)) new_keyframe = true;
    }
    // A second estimate of cur against ref, beside the kept one: its matches and inliers in
    // *aside; its time and its brute-force and guided rematching added to the frame's (work done
    // for the frame whether or not the estimate is kept).
    const auto estimate_aside = [&](const Reference& ref, FrameResult* aside, std::string* reason) {
      *aside = r;
      MotionEstimate estimate = Estimate(ref, cur, world_from_cur_pred, aside, reason);
      r.times = aside->times;
      r.fallbacks = aside->fallbacks;
      r.rematches = aside->rematches;
      return estimate;
    };
    // The keyframe fusion (below) measures a new keyframe again against the last frame: where
    // that frame was tracked (it has no SIFT features), by tracking the new keyframe's keypoints
    // back into it (track_fusion); else by SIFT on both, which with a second thread go side by
    // side.
    const bool fuse = options_.fuse_keyframe_pose && !recovered && last_.frame != key_.frame &&
                      last_.pose_from_features;
    const bool fuse_by_tracks = fuse && options_.track_fusion && !last_.has_features;
    if (new_keyframe && fuse && !fuse_by_tracks) EnsureFeatures(&cur, &r, &last_);
    if (new_keyframe) ensure_cur_features();
    if (new_keyframe && tracked) {
      // A keyframe's pose is in every pose after it: it is measured as without tracking, by
      // SIFT matching against the old keyframe, and that estimate replaces the tracked one
      // where it verifies. (The tracks' estimate drifts with their windows as the view changes,
      // which is why the keyframe is renewed. Synthetic robot, seeds 42 / 1, ATE 0.0110 /
      // 0.0127 -> 0.0067 / 0.0073 m; docs/benchmarks.md.)
      FrameResult again;
      std::string reason;
      MotionEstimate matched = estimate_aside(key_, &again, &reason);
      if (reason.empty()) {
        motion = std::move(matched);
        r = std::move(again);
        r.from_tracks = false;
      }
    }
    // world_from_cur = world_from_key * key_from_cur.
    cur.world_from_cam = key_.world_from_cam * motion.prev_from_cur;
    if (motion.unconstrained) {
      cur.world_from_cam_6dof = key_.world_from_cam_6dof * *motion.unconstrained;
      r.world_from_cam_6dof = cur.world_from_cam_6dof;
    }
    if (new_keyframe && fuse) {
      // The frame's error will be in every pose after it: measure it again against the last
      // frame and average the two verified poses, each weighted by its inliers (an estimate's
      // variance goes as one over its inliers; the last frame's own error is left out). Mean
      // of 12 seeds, fr1/xyz every 2nd ATE: 0.0141 -> 0.0118 m (docs/benchmarks.md).
      FrameResult again;
      std::string reason;
      std::optional<Rigid3d> last_from_cur;
      if (fuse_by_tracks) {
        // All the new keyframe's keypoints with a 3D point, tracked back into the last frame
        // from where the motion prior puts them (the prior the last frame's own tracks started
        // from; started from the keyframe's estimate instead, the tracks lean toward it:
        // docs/benchmarks.md). The tracking makes the keyframe's pyramid derivatives, which its
        // next frames need.
        std::vector<int> lifted;
        for (size_t i = 0; i < cur.points.size(); ++i)
          if (cur.points[i]) lifted.push_back(static_cast<int>(i));
        again = r;  // its counts and times, as estimate_aside's
        const MotionEstimate back = EstimateFromTracks(
            &cur, lifted, last_, last_.world_from_cam.inverse() * world_from_cur_pred, &again);
        r.times = again.times;
        reason = CheckMotion(options_.verify, back);
        if (reason.empty()) last_from_cur = back.prev_from_cur.inverse();
      } else {
        // The last frame's SIFT ran above.
        const MotionEstimate from_last = estimate_aside(last_, &again, &reason);
        if (reason.empty()) last_from_cur = from_last.prev_from_cur;
      }
      if (last_from_cur) {
        const double w = static_cast<double>(r.inliers) / (r.inliers + again.inliers);
        cur.world_from_cam =
            WeightedMean(cur.world_from_cam, last_.world_from_cam * *last_from_cur, w);
      }
    }
    // The velocity is what one estimate measured. After frames aligned by depth it is this
    // estimate's own, over its span from the keyframe: the difference from the last (aligned)
    // frame's pose would add that frame's error, which this estimate corrects, and the depth
    // alignment's next frames would carry it along the directions their surfaces leave free.
    // (Synthetic robot every 3rd frame, seed 42: a 15-inlier estimate correcting two aligned
    // frames by 5 cm sideways; nine aligned frames then slid 5 cm each, ATE 0.180 -> 0.029 m.)
    Advance(std::move(cur), new_keyframe, last_.pose_from_features ? last_ : key_);
    r.keyframe = new_keyframe;
    CorrectTilt(frame);
    r.status = recovered ? FrameStatus::kRecovered : FrameStatus::kAccepted;
    r.world_from_cam = last_.world_from_cam;
    r.velocity = LastVelocity();
    return r;
  }
  if (options_.depth_fallback && !last_.depth_m.empty()) {
    const Stopwatch t1;
    // The depth alignment keeps the prediction's translation where no surface constrains it,
    // and the aligned frames after it carry that velocity on: so it is measured over the
    // longest span one estimate measured, from the keyframe to the last frame when the last
    // frame's features were matched against it. (Two estimates against one keyframe differ by
    // their noise: in a feature-poor view 2 cm a frame with 15-20 inliers. Synthetic robot every
    // 3rd frame, seed 1: ATE 0.084 -> 0.019 m.)
    Rigid3d align_pred = world_from_cur_pred;
    if (last_.pose_from_features && key_.frame != last_.frame &&
        last_.color_timestamp > key_.color_timestamp)
      align_pred =
          PredictConstantVelocity(key_.world_from_cam, key_.color_timestamp, last_.world_from_cam,
                                  last_.color_timestamp, frame.color_timestamp);
    // Within a run of frames aligned by depth, against the run's depth keyframe first: each
    // alignment with the frame before adds its error to every pose after it (a few tenths of a
    // degree a frame on TUM's recordings). The keyframe holds while the alignment with it
    // succeeds and its surfaces constrain every direction: along a free one the translation is
    // the prediction's, which only the frame before keeps as near as one frame's motion
    // (synthetic robot, floor and one wall: 0.7-1.1 degrees off against a keyframe 4-6 frames
    // back).
    DepthAlignResult aligned;
    Rigid3d world_from_ref = last_.world_from_cam;
    if (options_.depth_keyframe && !last_.pose_from_features && depth_key_.frame >= 0 &&
        depth_key_.frame != last_.frame) {
      aligned = depth_aligner_->Align(depth_key_.depth_m, cur.depth_m,
                                      depth_key_.world_from_cam.inverse() * align_pred);
      if (aligned.success && aligned.constraint.free_directions.empty())
        world_from_ref = depth_key_.world_from_cam;
      else
        aligned.success = false;
    }
    if (!aligned.success) {
      aligned = depth_aligner_->Align(last_.depth_m, cur.depth_m,
                                      last_.world_from_cam.inverse() * align_pred);
      if (aligned.success) depth_key_ = {last_.depth_m, last_.world_from_cam, last_.frame};
    }
    r.times.ransac += t1.Seconds();
    if (aligned.success) {
      // The frame becomes the last estimated one; the keyframe stays (its sharp features are
      // what the next frame is matched against first).
      cur.world_from_cam =
          world_from_ref * (level_from_cam_ ? ProjectPlanar(*level_from_cam_, aligned.prev_from_cur)
                                            : aligned.prev_from_cur);
      // The 6-DOF chain goes on with the planar step: the depth alignment measures too little
      // to tell (along a free direction it has the prediction's translation).
      if (level_from_cam_)
        cur.world_from_cam_6dof =
            last_.world_from_cam_6dof * last_.world_from_cam.inverse() * cur.world_from_cam;
      cur.pose_from_features = false;
      Advance(std::move(cur), false, last_);
      CorrectTilt(frame);
      r.status = FrameStatus::kDepth;
      r.world_from_cam = last_.world_from_cam;
      r.velocity = LastVelocity();
      return r;
    }
    r.reason += "+" + aligned.reason;
  }
  r.world_from_cam = options_.predict_failed_frames ? world_from_cur_pred : last_.world_from_cam;
  r.world_from_cam.linear() = NearestRotation(r.world_from_cam.linear());
  if (options_.predict_failed_frames) r.velocity = LastVelocity();  // held: no motion
  // No restart from a frame that cannot be the reference (can_be_reference): the next one is
  // tried.
  if (options_.max_rejected_run > 0 && ++rejected_run_ >= options_.max_rejected_run &&
      can_be_reference()) {
    // The references are out of reach: restart from this frame at the pose just reported.
    cur.world_from_cam = cur.world_from_cam_6dof = r.world_from_cam;
    key_ = last_ = std::move(cur);
    has_before_ = false;
    rejected_run_ = 0;
    r.status = FrameStatus::kLost;
    r.keyframe = true;
  } else {
    r.status = options_.predict_failed_frames ? FrameStatus::kPredicted : FrameStatus::kRejected;
  }
  return r;
}

void Odometry::SetUpMotionModel(const Frame& first) {
  if (options_.motion != "planar") {
    std::ostringstream brief;
    brief << "6-DOF";
    if (gravity_)
      brief << ", roll and pitch pulled toward the accelerometer's gravity (time constant "
            << options_.gravity.time_constant_s << " s)";
    motion_brief_ = brief.str();
    return;
  }
  std::ostringstream brief;
  brief << std::fixed << std::setprecision(1) << "planar (x, z and yaw about the floor's normal)";
  if (options_.floor == "given") {
    level_from_cam_ = LevelFromFloorNormal(
        FloorNormalFromMount(options_.mount_pitch_deg, options_.mount_roll_deg));
    brief << ", mount given: pitch " << options_.mount_pitch_deg << " deg, roll "
          << options_.mount_roll_deg << " deg";
  } else if (options_.floor == "accelerometer") {
    if (!first.gravity_in_cam)
      throw std::runtime_error("--motion planar --floor accelerometer: frame " +
                               std::to_string(first.index) +
                               " has no accelerometer reading; use --floor depth or given");
    const Eigen::Vector3d normal = first.gravity_in_cam->normalized();
    level_from_cam_ = LevelFromFloorNormal(normal);
    const Eigen::Vector2d mount = MountFromFloorNormal(normal);
    brief << ", floor's normal from frame " << first.index << "'s accelerometer reading: pitch "
          << mount.x() << " deg, roll " << mount.y() << " deg (|a| " << std::setprecision(2)
          << first.gravity_in_cam->norm() << " m/s^2)";
  } else {
    Rng rng(options_.seed);
    const FloorFit fit = FitFloor(FloorFitOptions{}, calib_, first.depth_m, rng);
    if (!fit.success)
      throw std::runtime_error("--motion planar: no floor in the first frame's depth image (" +
                               fit.reason +
                               "); start with the floor in view, take it from the "
                               "accelerometer (--floor accelerometer) or give the camera's mount "
                               "with --floor given --mount-pitch DEG --mount-roll DEG");
    level_from_cam_ = fit.level_from_cam;
    brief << ", floor fitted in frame " << first.index << "'s depth: " << fit.Brief();
  }
  options_.refine.planar_level_from_cam = level_from_cam_;
  motion_brief_ = brief.str();
}

void Odometry::CorrectTilt(const Frame& frame) {
  if (!gravity_ || !frame.gravity_in_cam) return;
  // The accelerometer reads g - a. A camera turning at w while moving at v (both in its own
  // frame, the odometry's last velocity) accelerates by w x v toward the turn's centre: on a
  // robot's turn (0.4 m/s at 38 deg/s) 0.27 m/s^2, 1.6 degrees of tilt if taken for gravity
  // and nearly 1 g in magnitude, so the weight cannot tell. Put back, it leaves the changes of
  // speed, which average out over the time constant. (Measured on the synthetic robot's first
  // 740 frames, median tilt against the truth: 0.22 degrees without it, 0.03 with it.)
  const Velocity v = LastVelocity();
  const Eigen::Vector3d gravity =
      *frame.gravity_in_cam + v.rotation_per_s.cross(v.translation_per_s);
  const Rigid3d correction = gravity_->Update(last_.world_from_cam, gravity, frame.color_timestamp);
  for (Rigid3d* pose : {&key_.world_from_cam, &last_.world_from_cam, &world_from_before_,
                        &depth_key_.world_from_cam}) {
    *pose = correction * *pose;
    pose->linear() = NearestRotation(pose->linear());
  }
}

std::string Odometry::GravityBrief() const {
  if (!gravity_) return "";
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << "gravity: " << gravity_->readings()
    << " frames with an accelerometer reading, mean weight " << gravity_->mean_weight()
    << ", largest tilt against a reading " << gravity_->max_tilt_deg() << " deg (time constant "
    << options_.gravity.time_constant_s << " s)";
  return s.str();
}

Velocity Odometry::LastVelocity() const {
  if (!has_before_) return {};
  return VelocityOf(world_from_before_.inverse() * last_.world_from_cam,
                    last_.color_timestamp - before_color_time_);
}

void Odometry::Advance(Reference cur, bool new_keyframe, const Reference& measured_from) {
  cur.world_from_cam.linear() = NearestRotation(cur.world_from_cam.linear());
  cur.world_from_cam_6dof.linear() = NearestRotation(cur.world_from_cam_6dof.linear());
  world_from_before_ = measured_from.world_from_cam;
  before_color_time_ = measured_from.color_timestamp;
  has_before_ = true;
  if (new_keyframe) key_ = cur;
  last_ = std::move(cur);
  rejected_run_ = 0;
}

}  // namespace rgbdvo
