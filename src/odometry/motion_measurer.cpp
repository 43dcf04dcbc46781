#include "motion_measurer.hpp"

#include <algorithm>
#include <future>

#include "rgbdvo/estimation/depth_term.hpp"
#include "rgbdvo/estimation/motion_check.hpp"
#include "rgbdvo/estimation/planar_motion.hpp"
#include "rgbdvo/estimation/refine.hpp"
#include "rgbdvo/features/guided_matching.hpp"
#include "rgbdvo/features/matching.hpp"
#include "rgbdvo/sensor/camera.hpp"
#include "rgbdvo/util/stopwatch.hpp"

namespace rgbdvo {

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

// The value below which a fraction q of `values` lie (nearest rank); 0 for none.
float Percentile(std::vector<float> values, double q) {
  if (values.empty()) return 0;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(q * (values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

}  // namespace

MotionMeasurer::MotionMeasurer(const OdometryOptions& options, const Calibration& calib)
    : options_(options), calib_(calib), extractor_(options.features), rng_(options.seed) {}

void MotionMeasurer::SetLevel(const Eigen::Matrix3d& level_from_cam) {
  level_from_cam_ = level_from_cam;
  options_.refine.planar_level_from_cam = level_from_cam;
}

const cv::Mat& MotionMeasurer::DepthRaysFor(const cv::Size& size) {
  if (depth_rays_.size() != size) depth_rays_ = DepthRays(calib_, size);
  return depth_rays_;
}

MotionEstimate MotionMeasurer::FromMatches(const Reference& ref, const Reference& cur,
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
  if (estimate.success && options_.refine_enabled) Refine(ref, cur, pairs, &estimate);
  r->times.ransac += t0.Seconds();
  r->inliers = static_cast<int>(estimate.inliers.size());
  return estimate;
}

void MotionMeasurer::Refine(const Reference& ref, const Reference& cur,
                            const std::vector<PointPair>& pairs, MotionEstimate* estimate) {
  // Refine on the RANSAC inliers, measure the frame's noise scale there, then select inliers by
  // whitened error at that scale and refine on them until the selection settles.
  const double f = 0.5 * (calib_.fx + calib_.fy);
  const RansacResult& ransac = estimate->ransac;
  const Rigid3d T =
      RefineMotion(options_.refine, f, pairs, ransac.inliers, ransac.prev_from_cur).prev_from_cur;
  const NoiseScale noise = EstimateNoiseScale(options_.refine, f, pairs, ransac.inliers, T);
  estimate->pixel_noise = noise.pixel;
  const RefineOptions scaled = ScaleNoise(options_.refine, noise);
  std::optional<DepthPlaneTerm> dense;
  const auto add_depth_term = [&](const Rigid3d& at) {
    dense.emplace(calib_, depth_rays_, ref.depth_m, ref.depth_from_cam, cur.depth_points,
                  options_.refine.depth_noise_coeff, options_.lifting.max_depth_jump_ratio);
    // The depth camera saw the frame's motion blur too: its surfaces are trusted no better.
    dense->ScaleNoise(std::max(EstimateDepthTermScale(*dense, at), noise.pixel));
  };
  const bool depth_term =
      options_.depth_term_step > 0 && !ref.depth_m.empty() && !cur.depth_points.empty();
  if (depth_term && options_.depth_term_translation_std_m == 0) add_depth_term(T);
  SelectionRefinement selected =
      RefineWithInlierSelection(scaled, f, pairs, T, dense ? &*dense : nullptr);
  if (depth_term && !dense && selected.refine &&
      !(TranslationStd(options_.refine, f, pairs, selected.inliers,
                       selected.refine->prev_from_cur) <= options_.depth_term_translation_std_m)) {
    // The features leave the translation uncertain: the depth surfaces join, from the features'
    // motion.
    const Rigid3d from = selected.refine->prev_from_cur;
    add_depth_term(from);
    selected = RefineWithInlierSelection(scaled, f, pairs, from, &*dense);
  }
  if (!selected.refine) return;
  estimate->refine = selected.refine;
  estimate->prev_from_cur = estimate->refine->prev_from_cur;
  if (scaled.planar_level_from_cam) {
    RefineOptions free = scaled;
    free.planar_level_from_cam.reset();
    estimate->unconstrained = RefineMotion(free, f, pairs, selected.inliers,
                                           estimate->prev_from_cur, dense ? &*dense : nullptr)
                                  .prev_from_cur;
  }
  estimate->inliers = std::move(selected.inliers);
}

MotionEstimate MotionMeasurer::Match(const Reference& ref, const Reference& cur,
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
  MotionEstimate motion = FromMatches(ref, cur, cur.points, matches, r, &match_of_pair);
  *reason = CheckMotion(options_.verify, motion);
  // The kept estimate's inliers as keypoint pairs.
  const auto keep_inliers = [this](const std::vector<cv::DMatch>& kept,
                                   const std::vector<int>& kept_of_pair,
                                   const MotionEstimate& estimate) {
    matched_inliers_.clear();
    for (const int k : estimate.inliers) {
      const cv::DMatch& m = kept[kept_of_pair[k]];
      matched_inliers_.emplace_back(m.queryIdx, m.trainIdx);
    }
  };
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
    motion = FromMatches(ref, cur, cur.points, matches, r, &match_of_pair);
    *reason = CheckMotion(options_.verify, motion);
  }
  keep_inliers(matches, match_of_pair, motion);
  r->prediction_error_px =
      PredictionErrors(predicted, matches, match_of_pair, motion, cur.features);
  // The estimate from `other` replaces `motion` if it passes verification with at least `factor`
  // times its inliers; r's counts are the kept estimate's. Returns the other estimate's inliers
  // (0 when it fails verification).
  const auto replace_if_verified = [&](const std::vector<cv::DMatch>& other, size_t factor) {
    const int kept_matches = r->matches, kept_pairs = r->pairs, kept_inliers = r->inliers;
    std::vector<int> other_of_pair;
    MotionEstimate estimate = FromMatches(ref, cur, cur.points, other, r, &other_of_pair);
    const bool verified = CheckMotion(options_.verify, estimate).empty();
    const int inliers = verified ? r->inliers : 0;
    if (verified && estimate.inliers.size() >= factor * motion.inliers.size()) {
      r->prediction_error_px =
          PredictionErrors(predicted, other, other_of_pair, estimate, cur.features);
      motion = std::move(estimate);
      keep_inliers(other, other_of_pair, motion);
    } else {
      r->matches = kept_matches, r->pairs = kept_pairs, r->inliers = kept_inliers;
    }
    return inliers;
  };
  if (guided && options_.guided_rematch && reason->empty() &&
      Percentile(r->prediction_error_px, 0.99) > 0.5 * options_.guided_radius_px) {
    // The inliers reach into the outer half of the radius: the prior was off by about the
    // radius, right matches may lie beyond it. Around the estimate they lie within a few pixels.
    ++r->rematches;
    t0.Restart();
    const std::vector<cv::DMatch> again = MatchGuided(
        g, ref.features, PredictKeypoints(calib_, ref.points, motion.prev_from_cur.inverse()),
        cur.features);
    r->times.matching += t0.Seconds();
    const int first_inliers = r->inliers;
    const int again_inliers = replace_if_verified(again, 1);
    // Fewer inliers around itself, and few: a wrong motion a handful of wrong matches within
    // the prior's window may agree on. Brute force decides, with at least twice the inliers.
    if (!brute_forced && again_inliers < first_inliers &&
        first_inliers < 2 * options_.verify.min_inliers)
      replace_if_verified(match_all(), 2);
  }
  return motion;
}

void MotionMeasurer::EnsureFeatures(Reference* ref, FrameResult* r, Reference* beside) {
  // Extract is const and reentrant (the feature workers share it); beside's time counts as the
  // stage's all the same.
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

MotionEstimate MotionMeasurer::Track(Reference* ref, const std::vector<int>& tracked,
                                     const Reference& cur, const Rigid3d& cur_from_ref_pred,
                                     FrameResult* r) {
  Stopwatch t0;
  // The reference is tracked from: its pyramid gets the derivatives once.
  if (!HasDerivatives(ref->pyramid))
    ref->pyramid = MakeTrackingPyramid(options_.tracking, ref->grey, /*with_derivatives=*/true);
  // Each tracked keypoint starts where the motion prior puts it (where it was, without one).
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
  MotionEstimate motion = FromMatches(*ref, cur, cur_points, matches, r, &match_of_pair);
  r->prediction_error_px.clear();
  for (int p : motion.inliers) {
    const size_t k = track_of_match[match_of_pair[p]];
    if (predicted[k])
      r->prediction_error_px.push_back(static_cast<float>(
          (*predicted[k] - Eigen::Vector2d((*landed[k]).x, (*landed[k]).y)).norm()));
  }
  return motion;
}

}  // namespace rgbdvo
