#include "tracker.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "motion_model.hpp"
#include "rgbdvo/estimation/depth_term.hpp"
#include "rgbdvo/estimation/motion_check.hpp"
#include "rgbdvo/estimation/planar_motion.hpp"
#include "rgbdvo/geometry/motion_prior.hpp"
#include "rgbdvo/util/stopwatch.hpp"

namespace rgbdvo {

namespace {

// True when `image` is the only header of its buffer (allocated by OpenCV, continuous): kept, it
// cannot change under the odometry. A buffer someone else still refers to may be written again
// (a caller reading the next frame into the same cv::Mat): that one is copied.
bool SoleOwner(const cv::Mat& image) {
  return image.u != nullptr && image.u->refcount == 1 && image.isContinuous();
}

}  // namespace

Tracker::Tracker(const OdometryOptions& options, const Calibration& calib)
    : options_(options), calib_(calib), measurer_(options, calib) {
  if (options_.depth_fallback) {
    DepthAlignOptions d;
    d.max_translation_m = options_.verify.max_translation_m;
    d.max_rotation_deg = options_.verify.max_rotation_deg;
    d.depth_noise_coeff = options_.refine.depth_noise_coeff;
    depth_aligner_ = std::make_unique<DepthAligner>(d, calib_);
  }
  if (options_.gravity_correction) gravity_.emplace(options_.gravity);
  if (options_.local_map.enabled && !options_.motion.planar() && !options_.gravity_correction)
    map_ = std::make_unique<LocalMap>(options_, calib_);
}

// By value on purpose: the frame's own depth buffer is kept where nothing else refers to it.
// NOLINTNEXTLINE(performance-unnecessary-value-param)
FrameResult Tracker::Track(Frame frame, std::optional<Features> features) {
  Current c = Begin(frame, std::move(features));
  if (phase_ == Phase::kNoReference) return Start(frame, &c);
  Measure(&c);
  if (c.measured != Measured::kNothing) return Accept(frame, &c);
  if (options_.depth_fallback && !last_.depth_m.empty() && AlignDepth(frame, &c)) return c.r;
  return GiveUp(&c);
}

// ---- begin --------------------------------------------------------------------------------

Tracker::Current Tracker::Begin(const Frame& frame, std::optional<Features> features) {
  Current c;
  c.r.frame = frame.index;
  // The pose is the camera's at the colour image's time: the keypoints are seen then. Colour
  // times are also distinct, where two colour frames can share one depth frame and its time.
  c.r.timestamp = frame.color_timestamp;
  c.r.depth_timestamp = frame.timestamp;
  c.r.features = features ? static_cast<int>(features->size()) : 0;
  // Constant velocity from the last two estimated frames, timed by the colour images (the depth
  // images' times are irregular).
  c.world_from_pred = Moving()
                          ? PredictConstantVelocity(before_.world_from_cam, before_.color_timestamp,
                                                    last_.world_from_cam, last_.color_timestamp,
                                                    frame.color_timestamp)
                          : last_.world_from_cam;
  c.ref = MakeReference(frame, std::move(features), DepthFromColor(frame), &c.r);
  return c;
}

Rigid3d Tracker::DepthFromColor(const Frame& frame) const {
  // The camera's motion from the colour image's time to the depth image's at the last velocity,
  // when the offset is within the span that velocity was measured over.
  if (!Moving() || !options_.compensate_depth_delay) return Rigid3d::Identity();
  const double depth_delay = frame.timestamp - frame.color_timestamp;
  const double span = last_.color_timestamp - before_.color_timestamp;
  if (!(std::abs(depth_delay) <= span)) return Rigid3d::Identity();
  return ScaleMotion(before_.world_from_cam.inverse() * last_.world_from_cam, depth_delay / span)
      .inverse();
}

Reference Tracker::MakeReference(const Frame& frame, std::optional<Features> features,
                                 const Rigid3d& depth_from_color, FrameResult* r) {
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
  if (options_.depth_term_step > 0)
    cur.depth_points =
        SampleDepthPoints(measurer_.DepthRaysFor(frame.depth_m.size()), frame.depth_m,
                          depth_from_color.inverse(), options_.depth_term_step);
  r->times.lifting += t0.Seconds();
  if (options_.track_between_keyframes) {
    // What SIFT needs later and the pyramid to track into, without derivatives until the frame
    // is tracked from (timed with matching, which the tracking replaces).
    const Stopwatch t1;
    cur.grey = GreyImage(frame.bgr);
    cur.pyramid = MakeTrackingPyramid(options_.tracking, cur.grey, /*with_derivatives=*/false);
    r->times.matching += t1.Seconds();
  }
  return cur;
}

// ---- start --------------------------------------------------------------------------------

FrameResult Tracker::Start(const Frame& frame, Current* c) {
  if (!CanBeReference(c) && !DepthToAlign(frame)) {
    // No reference yet: reported at the origin, where the first reference will be.
    c->r.reason = "reference_points<" + std::to_string(options_.verify.min_inliers);
    c->r.status = options_.predict_failed_frames ? FrameStatus::kPredicted : FrameStatus::kRejected;
    return std::move(c->r);
  }
  MotionModelSetup model = SetUpMotionModel(options_, calib_, frame);
  level_from_cam_ = model.level_from_cam;
  motion_brief_ = std::move(model.brief);
  if (level_from_cam_) measurer_.SetLevel(*level_from_cam_);
  phase_ = Phase::kRunning;
  Restart(std::move(c->ref));
  CorrectTilt(frame);
  c->r.status = FrameStatus::kFirst;
  c->r.keyframe = true;
  return std::move(c->r);
}

void Tracker::EnsureCurrentFeatures(Current* c) {
  measurer_.EnsureFeatures(&c->ref, &c->r);
  c->r.features = static_cast<int>(c->ref.features.size());
}

bool Tracker::CanBeReference(Current* c) {
  // A frame with fewer points than a verified motion needs inliers (no depth yet, a blank wall,
  // a covered lens) cannot be matched by the frames after it.
  EnsureCurrentFeatures(c);
  const KeypointPoints& points = c->ref.points;
  return std::count_if(points.begin(), points.end(), [](const auto& p) { return p.has_value(); }) >=
         options_.verify.min_inliers;
}

bool Tracker::DepthToAlign(const Frame& frame) const {
  // The first reference may also be a frame whose depth the depth fallback can align the next
  // frames with: readings on at least half of it, the majority DepthAligner needs to agree.
  if (!options_.depth_fallback || frame.depth_m.empty()) return false;
  const cv::Mat readings = (frame.depth_m >= calib_.min_depth_m) &
                           (frame.depth_m <= calib_.max_depth_m) & (frame.depth_m > 0);
  return 2 * static_cast<size_t>(cv::countNonZero(readings)) >= frame.depth_m.total();
}

// ---- measure ------------------------------------------------------------------------------

void Tracker::Measure(Current* c) {
  FrameResult& r = c->r;
  if (options_.track_between_keyframes && key_.has_features && key_use_ == KeyframeUse::kTrack) {
    c->motion = TrackFromKeyframe(c);
    const bool verified = CheckMotion(options_.verify, c->motion).empty();
    c->tracks_failed = !verified;
    r.from_tracks = verified;
    if (verified) {
      c->measured = Measured::kTracks;
      return;
    }
  }
  EnsureCurrentFeatures(c);
  c->motion = measurer_.Match(key_, c->ref, c->world_from_pred, &r, &r.reason);
  if (r.reason.empty()) {
    c->measured = Measured::kKeyframeMatches;
    c->keyframe_matches = {key_.frame, measurer_.matched_inliers()};
    return;
  }
  if (last_.frame == key_.frame) return;
  // The keyframe is out of reach: the last estimated frame, which then becomes the keyframe.
  measurer_.EnsureFeatures(&last_, &r);
  std::string reason;
  MotionEstimate from_last = measurer_.Match(last_, c->ref, c->world_from_pred, &r, &reason);
  if (!reason.empty()) return;
  key_ = last_;
  key_use_ = KeyframeUse::kTrack;
  c->motion = std::move(from_last);
  r.reason.clear();
  c->measured = Measured::kLastFrameMatches;
}

MotionEstimate Tracker::TrackFromKeyframe(Current* c) {
  if (key_.tracked.empty()) {
    std::vector<bool> usable(key_.points.size());
    for (size_t i = 0; i < usable.size(); ++i) usable[i] = key_.points[i].has_value();
    key_.tracked = SelectSpread(key_.features.keypoints, usable, key_.grey.size(),
                                options_.tracking.max_points);
  }
  return measurer_.Track(&key_, key_.tracked, c->ref,
                         c->world_from_pred.inverse() * key_.world_from_cam, &c->r);
}

// ---- accept -------------------------------------------------------------------------------

FrameResult Tracker::Accept(const Frame& frame, Current* c) {
  FrameResult& r = c->r;
  Reference& cur = c->ref;
  const bool tracked = c->measured == Measured::kTracks;
  const bool recovered = c->measured == Measured::kLastFrameMatches;
  const bool new_keyframe = DecideKeyframe(c);
  // The fusion measures a new keyframe again against the last frame, by SIFT on both (side by
  // side with a second thread).
  const bool fuse = new_keyframe && options_.fuse_keyframe_pose && !recovered &&
                    last_.frame != key_.frame && last_.pose_from_features;
  if (fuse) measurer_.EnsureFeatures(&cur, &r, &last_);
  if (new_keyframe) EnsureCurrentFeatures(c);
  if (new_keyframe && tracked) {
    // A keyframe's pose is in every pose after it, and the tracks drift with their windows: it
    // is measured by SIFT matching against the old keyframe where that verifies.
    FrameResult again;
    std::string reason;
    MotionEstimate matched = MeasureAside(key_, c, &again, &reason);
    if (reason.empty()) {
      c->motion = std::move(matched);
      c->keyframe_matches = {key_.frame, measurer_.matched_inliers()};
      r = std::move(again);
      r.from_tracks = false;
    }
  }
  cur.world_from_cam = key_.world_from_cam * c->motion.prev_from_cur;
  if (c->motion.unconstrained) {
    cur.world_from_cam_6dof = key_.world_from_cam_6dof * *c->motion.unconstrained;
    r.world_from_cam_6dof = cur.world_from_cam_6dof;
  }
  if (fuse) FuseWithLastFrame(c);
  // The velocity is what one estimate measured: after depth-aligned frames, this estimate's own
  // from the keyframe (the last frame's pose would add the error this estimate corrects).
  Advance(std::move(cur), new_keyframe, last_.pose_from_features ? last_ : key_);
  if (new_keyframe) AdjustWithMap(c->keyframe_matches, &r);
  r.keyframe = new_keyframe;
  CorrectTilt(frame);
  r.status = recovered ? FrameStatus::kRecovered : FrameStatus::kAccepted;
  r.world_from_cam = last_.world_from_cam;
  r.velocity = LastVelocity();
  return std::move(r);
}

bool Tracker::DecideKeyframe(Current* c) {
  const bool tracked = c->measured == Measured::kTracks;
  const bool recovered = c->measured == Measured::kLastFrameMatches;
  if (key_.first_inliers < 0) key_.first_inliers = c->r.inliers;
  // Tracks failed where SIFT still reaches the keyframe (a feature-poor view, a blurred frame):
  // the keyframe stays, its next frames matched by SIFT; renewing it here would chain poses
  // frame to frame where matches are fewest.
  if (c->tracks_failed && !recovered) key_use_ = KeyframeUse::kMatch;
  bool new_keyframe = (c->tracks_failed && recovered) ||
                      !(c->r.inliers >= options_.keyframe_inlier_ratio * key_.first_inliers &&
                        options_.keyframe_inlier_ratio > 0);
  if (tracked && options_.track_stale_noise_ratio > 0) {
    // Tracks going stale raise their pixel noise, which the inlier count does not show
    // (TrackStaleness); the bar is the least noise on the keyframe's tracked frames so far.
    if (!key_.staleness) key_.staleness.emplace(options_.track_stale_noise_ratio);
    if (key_.staleness->Stale(c->motion.pixel_noise)) new_keyframe = true;
  }
  return new_keyframe;
}

MotionEstimate Tracker::MeasureAside(const Reference& ref, Current* c, FrameResult* aside,
                                     std::string* reason) {
  // A second estimate beside the kept one, its counts in *aside; its time and fallbacks are
  // the frame's whether or not it is kept.
  *aside = c->r;
  MotionEstimate estimate = measurer_.Match(ref, c->ref, c->world_from_pred, aside, reason);
  c->r.times = aside->times;
  c->r.fallbacks = aside->fallbacks;
  c->r.rematches = aside->rematches;
  return estimate;
}

void Tracker::FuseWithLastFrame(Current* c) {
  // A new keyframe's error is in every pose after it: measured again against the last frame,
  // the two verified poses averaged, each weighted by its inliers (variance ~ 1 / inliers).
  FrameResult again;
  std::string reason;
  const MotionEstimate from_last = MeasureAside(last_, c, &again, &reason);
  if (!reason.empty()) return;
  const double w = static_cast<double>(c->r.inliers) / (c->r.inliers + again.inliers);
  c->ref.world_from_cam =
      WeightedMean(c->ref.world_from_cam, last_.world_from_cam * from_last.prev_from_cur, w);
}

// ---- align depth --------------------------------------------------------------------------

bool Tracker::AlignDepth(const Frame& frame, Current* c) {
  FrameResult& r = c->r;
  Reference& cur = c->ref;
  const Stopwatch t1;
  // The alignment keeps the prediction's translation where no surface constrains it: predict
  // over the longest span one estimate measured, from the keyframe to the last frame.
  Rigid3d align_pred = c->world_from_pred;
  if (last_.pose_from_features && key_.frame != last_.frame &&
      last_.color_timestamp > key_.color_timestamp)
    align_pred =
        PredictConstantVelocity(key_.world_from_cam, key_.color_timestamp, last_.world_from_cam,
                                last_.color_timestamp, frame.color_timestamp);
  // Within a run of depth-aligned frames, against the run's depth keyframe first (each
  // frame-to-frame alignment adds its error), while it succeeds and constrains every direction.
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
  if (!aligned.success) {
    r.reason += "+" + aligned.reason;
    return false;
  }
  // The frame becomes the last estimated one; the keyframe stays (its sharp features are what
  // the next frame is matched against first).
  cur.world_from_cam =
      world_from_ref * (level_from_cam_ ? ProjectPlanar(*level_from_cam_, aligned.prev_from_cur)
                                        : aligned.prev_from_cur);
  // The 6-DOF chain goes on with the planar step (the alignment measures too little to tell).
  if (level_from_cam_)
    cur.world_from_cam_6dof =
        last_.world_from_cam_6dof * last_.world_from_cam.inverse() * cur.world_from_cam;
  cur.pose_from_features = false;
  Advance(std::move(cur), false, last_);
  CorrectTilt(frame);
  r.status = FrameStatus::kDepth;
  r.world_from_cam = last_.world_from_cam;
  r.velocity = LastVelocity();
  return true;
}

// ---- give up ------------------------------------------------------------------------------

FrameResult Tracker::GiveUp(Current* c) {
  FrameResult& r = c->r;
  r.world_from_cam = options_.predict_failed_frames ? c->world_from_pred : last_.world_from_cam;
  r.world_from_cam.linear() = NearestRotation(r.world_from_cam.linear());
  if (options_.predict_failed_frames) r.velocity = LastVelocity();  // held: no motion
  // No restart from a frame that cannot be the reference: the next one is tried.
  if (options_.max_rejected_run > 0 && ++rejected_run_ >= options_.max_rejected_run &&
      CanBeReference(c)) {
    // The references are out of reach: restart from this frame at the pose just reported.
    c->ref.world_from_cam = c->ref.world_from_cam_6dof = r.world_from_cam;
    Restart(std::move(c->ref));
    r.status = FrameStatus::kLost;
    r.keyframe = true;
  } else {
    r.status = options_.predict_failed_frames ? FrameStatus::kPredicted : FrameStatus::kRejected;
  }
  return std::move(r);
}

// ---- bookkeeping --------------------------------------------------------------------------

void Tracker::Advance(Reference cur, bool new_keyframe, const Reference& measured_from) {
  cur.world_from_cam.linear() = NearestRotation(cur.world_from_cam.linear());
  cur.world_from_cam_6dof.linear() = NearestRotation(cur.world_from_cam_6dof.linear());
  before_ = {true, measured_from.world_from_cam, measured_from.color_timestamp};
  if (new_keyframe) {
    key_ = cur;
    key_use_ = KeyframeUse::kTrack;
  }
  last_ = std::move(cur);
  rejected_run_ = 0;
}

void Tracker::Restart(Reference ref) {
  key_ = ref;
  key_use_ = KeyframeUse::kTrack;
  last_ = std::move(ref);
  before_.known = false;
  rejected_run_ = 0;
  if (map_) {
    map_->Clear();
    map_->AddKeyframe(key_);
  }
}

void Tracker::AdjustWithMap(const KeyframeMatches& matches, FrameResult* r) {
  if (!map_) return;
  const Stopwatch t0;
  const Rigid3d correction = map_->AddKeyframe(key_, matches) * key_.world_from_cam.inverse();
  for (Rigid3d* pose : {&key_.world_from_cam, &last_.world_from_cam, &before_.world_from_cam,
                        &depth_key_.world_from_cam}) {
    *pose = correction * *pose;
    pose->linear() = NearestRotation(pose->linear());
  }
  r->times.local_map += t0.Seconds();
}

void Tracker::CorrectTilt(const Frame& frame) {
  if (!gravity_ || !frame.gravity_in_cam) return;
  // The accelerometer reads g - a; a turn at w while moving at v accelerates by w x v toward
  // the turn's centre, which the reading's weight cannot tell from gravity: put back.
  const Velocity v = LastVelocity();
  const Eigen::Vector3d gravity =
      *frame.gravity_in_cam + v.rotation_per_s.cross(v.translation_per_s);
  const Rigid3d correction = gravity_->Update(last_.world_from_cam, gravity, frame.color_timestamp);
  for (Rigid3d* pose : {&key_.world_from_cam, &last_.world_from_cam, &before_.world_from_cam,
                        &depth_key_.world_from_cam}) {
    *pose = correction * *pose;
    pose->linear() = NearestRotation(pose->linear());
  }
}

std::string Tracker::GravityBrief() const {
  if (!gravity_) return "";
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << "gravity: " << gravity_->readings()
    << " frames with an accelerometer reading, mean weight " << gravity_->mean_weight()
    << ", largest tilt against a reading " << gravity_->max_tilt_deg() << " deg (time constant "
    << options_.gravity.time_constant_s << " s)";
  return s.str();
}

bool Tracker::Moving() const {
  return before_.known && last_.color_timestamp > before_.color_timestamp;
}

Velocity Tracker::LastVelocity() const {
  if (!before_.known) return {};
  return VelocityOf(before_.world_from_cam.inverse() * last_.world_from_cam,
                    last_.color_timestamp - before_.color_timestamp);
}

}  // namespace rgbdvo
