#pragma once
// The visual odometry loop: features -> matches -> 3D pairs -> RANSAC -> verification -> pose.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rgbdvo/estimation/motion_check.hpp"
#include "rgbdvo/estimation/ransac.hpp"
#include "rgbdvo/estimation/refine.hpp"
#include "rgbdvo/features/features.hpp"
#include "rgbdvo/features/matching.hpp"
#include "rgbdvo/features/track_options.hpp"
#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/geometry/motion_prior.hpp"
#include "rgbdvo/odometry/gravity_correction.hpp"
#include "rgbdvo/odometry/point_pairs.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame.hpp"

namespace rgbdvo {

// The motion model: kSixDof, any rigid motion (the paper), or kPlanar: the camera is rigidly
// mounted on a robot driving on a flat floor, so each frame's motion is a turn about the floor's
// normal and a translation along the floor. 3 degrees of freedom instead of 6: 2-pair RANSAC
// hypotheses (EstimatePlanarRansac), a refinement of those 3 parameters, the depth fallback's
// estimate projected onto them (ProjectPlanar).
enum class MotionModelKind { kSixDof, kPlanar };
// With the planar model, where the floor's normal in the camera frame comes from: a plane fitted
// to the first frame's depth image (FitFloor; the floor must be in view), the first frame's
// accelerometer reading (the robot standing still), or the mount as given.
enum class FloorSource { kDepth, kAccelerometer, kGiven };

struct MotionOptions {
  MotionModelKind model = MotionModelKind::kSixDof;
  FloorSource floor = FloorSource::kDepth;
  double mount_pitch_deg = 0;  // with floor kGiven: the camera's pitch, deg (+: looks down)
  double mount_roll_deg = 0;   // with floor kGiven: its roll, deg (+: the floor's normal leans
                               // to the camera's +x; FloorFit's convention)
  bool planar() const { return model == MotionModelKind::kPlanar; }
};

// The local map (docs/decisions/0048-local-map.md): each keyframe's keypoints with a 3D point
// become map points; a later keyframe that sees one (where it projects, within search_radius_px,
// by descriptor) adds an observation. After each new keyframe, it and the keyframes sharing the
// most points with it (window_keyframes in all) are adjusted with their points (bundle
// adjustment on the refinement's residuals), the keyframes outside that see those points held
// fixed; the frames after it are measured from the adjusted pose. The map keeps the last
// max_keyframes keyframes, and a point only while a keyframe after its first sees it. Off by
// default: it does not yet beat the keyframe chain on the recordings measured.
struct LocalMapOptions {
  bool enabled = false;
  int window_keyframes = 10;
  int max_keyframes = 30;
  double search_radius_px = 8;
  int max_iterations = 10;  // Levenberg-Marquardt iterations at most per adjustment
  void Check() const;
};

struct OdometryOptions {
  FeatureOptions features;
  MatchOptions matching;
  // Guided matching: a reference keypoint is compared only with the current keypoints
  // within this radius of where the constant-velocity motion prior puts it (colour pixels; ratio
  // and mutual check from `matching`); an estimate that fails verification is redone with
  // brute-force matching. 0 = brute force only (the paper). See GuidedMatchOptions::radius_px.
  double guided_radius_px = 30;
  // Guided matching again, around the estimate, when its inliers' prediction error reaches the
  // outer half of the radius (99th percentile above radius / 2): the prior was off by about as
  // much as the radius (the motion reversed, or a thinned recording's longer steps), so right
  // matches lay beyond it; the second estimate replaces the first if it passes verification
  // with at least as many inliers. When it finds fewer and the first has fewer than twice
  // verify.min_inliers, the first may be a wrong motion a few wrong matches agree on: brute
  // force then decides, its estimate taken with at least twice the inliers.
  bool guided_rematch = true;
  LiftOptions lifting;
  RansacOptions ransac;
  MotionCheckOptions verify;
  // Refine the RANSAC motion on reprojection and depth residuals (false = the paper's SVD only).
  bool refine_enabled = true;
  RefineOptions refine;
  // Keyframes: frames are matched against the keyframe, which is replaced by the current frame
  // when its inliers fall below this fraction of those of the keyframe's first match (drift
  // then grows per keyframe, not per frame). 0 = every accepted frame is the next reference,
  // as in the paper.
  double keyframe_inlier_ratio = 0.7;
  // A new keyframe's pose is in every pose after it, and its estimate against the old keyframe
  // is the weakest of that keyframe's life. So it is measured twice: also against the last
  // frame, and the two verified poses are averaged, weighted by their inliers (rotation along
  // the geodesic). false = the estimate against the old keyframe alone.
  bool fuse_keyframe_pose = true;
  // Between keyframes, the keyframe's keypoints are tracked into each frame (pyramidal
  // Lucas-Kanade from where the motion prior puts them, TrackPoints) and the tracked pairs go
  // through RANSAC, the refinement and verification as matches do; SIFT runs only where it is
  // needed: on a frame that becomes a keyframe, on the frame before it (keyframe fusion), and
  // where the tracked estimate fails verification (that frame and the keyframe's next ones are
  // then matched as without tracking: the tracks no longer carry the motion). A new keyframe
  // also when the tracks go stale: the refinement's measured pixel noise on them above
  // track_stale_noise_ratio times the least measured on the keyframe's tracked frames so far
  // (TrackStaleness). A frame that becomes a keyframe takes its pose from SIFT matching against
  // the old keyframe where that verifies. Less CPU than SIFT on every frame, as accurate
  // (docs/decisions/0038-tracking-by-default.md). false = SIFT and matching on every frame, as
  // the paper (--preset paper).
  bool track_between_keyframes = true;
  TrackOptions tracking;
  double track_stale_noise_ratio = 1.5;
  // 6-DOF without gravity correction only: the planar model and the correction constrain poses
  // the adjustment would not keep.
  LocalMapOptions local_map;
  // After this many rejected frames in a row the reference is given up: the current frame
  // becomes the new reference at the last known pose (status "lost"), so a stuck reference
  // cannot freeze the trajectory forever. 0 = never.
  int max_rejected_run = 30;
  // When the features give no verified motion, align the frame's depth image with the last
  // estimated frame's or the depth keyframe's (depth_keyframe, below); status "icp".
  // DepthAligner: ICP from several starts, accepted only when the majority of the overlapping
  // depth agrees (docs/decisions/0007-depth-fallback-verified.md). false = features only (the
  // paper).
  bool depth_fallback = true;
  // In a run of frames aligned by depth, align each with the run's depth keyframe (the frame
  // the last alignment against the frame before was made with) while that succeeds and its
  // surfaces constrain every direction; frame to frame otherwise, where the alignments add
  // their errors up (docs/decisions/0026-depth-keyframe.md). false = always against the frame
  // before.
  bool depth_keyframe = true;
  // A frame whose motion cannot be estimated is reported at the constant-velocity prediction
  // (status "predicted"), so a failure run does not freeze the trajectory; false = at the last
  // accepted pose (status "rejected", the paper).
  bool predict_failed_frames = true;
  // The depth image may be taken up to half a frame before or after the colour image (TUM fr1:
  // +-15 ms); in a fast turn the scene moves by several pixels meanwhile. Lift each keypoint
  // where its point lies in the depth image, moved by the predicted velocity over the time
  // difference (LiftKeypointsAcrossTime); false = at the same pixel (the paper).
  bool compensate_depth_delay = true;
  // The depth surfaces in the refinement (DepthPlaneTerm): point-to-plane residuals of the
  // current depth image's points on a grid of every n-th pixel against the reference's depth
  // image, added where the features alone leave the translation uncertain: their TranslationStd
  // (at the model's noise, so by the matches' number and layout, not the frame's blur) above
  // depth_term_translation_std_m. Such matches are few, or crowd on one surface far away where a
  // turn and a slide look alike; the depth surfaces (a floor, a wall) pin what they leave free.
  // Where the features pin the translation, the depth term adds little and under a fast turn
  // its surfaces (read by another camera at another time) err more than the model says
  // (docs/decisions/0014-depth-term-gated.md). depth_term_step 0 = features only (the paper);
  // depth_term_translation_std_m 0 = on every frame.
  int depth_term_step = 16;
  double depth_term_translation_std_m = 0.004;
  MotionOptions motion;
  // Correct roll and pitch drift with the frames' accelerometer readings (GravityCorrection;
  // 6-DOF only: the planar model holds them fixed).
  bool gravity_correction = false;
  GravityOptions gravity;
  // Use the calibration's lens distortion (dist_ir) when lifting pixels (the paper: no).
  bool undistort = true;
  uint32_t seed = 42;  // RANSAC random generator seed (fixed: runs are reproducible)
  void Check() const;
  std::string ToString() const;  // the effective configuration, one "key = value" per line
  // True when frames must carry accelerometer readings (Frame::gravity_in_cam).
  bool NeedsAccelerometer() const {
    return gravity_correction || (motion.planar() && motion.floor == FloorSource::kAccelerometer);
  }
};

// Named configurations: "default" (rgbdvo's most accurate) and "paper" (exactly Fiala & Ufkes
// 2011: ratio-test matching between successive frames, 4-point RANSAC at 1.5 cm, SVD refinement,
// pinhole model). Throws std::invalid_argument for another name.
OdometryOptions PresetOptions(const std::string& name);

// kFirst: the first reference, the origin (the first frame with at least verify.min_inliers 3D
// points; the frames before it are kPredicted / kRejected at the origin, reason
// "reference_points<N"). kAccepted: estimated against the keyframe. kRecovered: the keyframe
// failed, estimated against the last accepted frame. kDepth: the features failed, the depth
// images aligned by ICP. kPredicted / kRejected: no estimate, reported at the prediction / at the
// last accepted pose (predict_failed_frames). kLost: the references were given up here.
enum class FrameStatus { kFirst, kAccepted, kRecovered, kDepth, kPredicted, kRejected, kLost };

// True for the statuses whose pose comes from matched features (or the first frame).
bool HasFeatureEstimate(FrameStatus status);
// True for those and kDepth: the pose was measured, not predicted or held.
bool HasEstimate(FrameStatus status);

// Seconds spent per stage for one frame (for bench/speed).
struct StageTimes {
  double features = 0, matching = 0, lifting = 0, ransac = 0;
  double local_map = 0;  // the map's association and bundle adjustment
};

struct FrameResult {
  int frame = 0;
  double timestamp = 0;        // seconds: the colour image's time (Frame::color_timestamp)
  double depth_timestamp = 0;  // seconds: the paired depth image's time (Frame::timestamp)
  // The colour camera's pose at `timestamp`, in the first reference's colour camera frame: the
  // IR camera's (whose frame the 3D points are in) moved by ColorCenterInIr. The two differ
  // where the calibration has a disparity term (unregistered depth); registered depth and eq. 1
  // alone take them as one.
  Rigid3d world_from_cam = Rigid3d::Identity();
  // The (colour) camera's velocity at this frame, from the last two estimated frames once this one
  // is processed, timed by their colour images: for an estimated frame from the one before to this
  // one (after frames aligned by depth, from the keyframe its features were matched against),
  // for a predicted frame the velocity it was predicted with; zero for a held (rejected)
  // frame and before two frames were estimated.
  // Moves the pose to another time, e.g. the depth image's (MoveAtVelocity).
  Velocity velocity;
  // With the planar motion model: the pose the same estimates would give with all 6 degrees of
  // freedom, chained alongside (PlanarityCheck); set for feature estimates only (the chain
  // takes the planar step across depth-aligned frames).
  std::optional<Rigid3d> world_from_cam_6dof;
  int features = 0;
  int matches = 0;
  int pairs = 0;  // matches with depth at both ends
  int inliers = 0;
  // Estimates redone with brute-force matching: the guided one failed verification, or it had
  // few inliers and matching around it found fewer (guided_rematch).
  int fallbacks = 0;
  // Estimates redone with guided matching around the first estimate (guided_rematch).
  int rematches = 0;
  // With track_between_keyframes: the pose was measured from the keyframe's keypoints tracked
  // into the frame (not from matches), and the SIFT extractions the odometry ran for the frame
  // (its own, and a reference's for the keyframe fusion or a fallback). Without it features
  // come with the frame: false and 0.
  bool from_tracks = false;
  int sift_runs = 0;
  // The frame became the keyframe the next frames are measured against (the first frame, a
  // renewal, a restart after "lost").
  bool keyframe = false;
  // For each final inlier: the distance from where the motion prior predicted its reference
  // keypoint to the current keypoint it was matched with, colour pixels.
  std::vector<float> prediction_error_px;
  FrameStatus status = FrameStatus::kFirst;
  std::string reason;  // why the features failed (icp, predicted, rejected, lost), "" otherwise
  StageTimes times;
  // "first", "accepted", "recovered", "icp:<reason>", "predicted:<reason>", "rejected:<reason>"
  // or "lost:<reason>" (no commas); <reason> says why the features failed.
  std::string StatusString() const;
};

// Tracking policy (src/odometry/tracker.hpp names its stages). Each frame is measured against
// the keyframe (its keypoints tracked, else matched: guided by the prediction, then by brute
// force), then against the last accepted frame. When neither passes verification the
// depth images are aligned (depth_fallback); when that fails too the frame is reported at the
// constant-velocity prediction (or held, see predict_failed_frames) and the next frame is matched
// against the same references, never against the failed one, so the motion across the failure is
// still measured, not lost.
class Tracker;

// The smallest image processed: the depth fallback halves it, then builds an image pyramid.
inline const cv::Size kMinImageSize(64, 48);

class Odometry {
 public:
  Odometry(const OdometryOptions& options, const Calibration& calib);
  ~Odometry();
  Odometry(const Odometry&) = delete;
  Odometry& operator=(const Odometry&) = delete;
  // Extracts features from frame.bgr, then as below. The odometry keeps the frame's depth
  // image for the frames after it: a copy, or the image itself where the call holds the only
  // reference to it (a frame handed over with std::move, whose images nothing else refers to).
  // Throws std::runtime_error naming frame.name for an image smaller than kMinImageSize or of
  // another size than the first frame's.
  FrameResult Process(Frame frame);
  // With features already extracted from frame.bgr (e.g. on another thread).
  FrameResult Process(Frame frame, Features features);
  // True when Process(frame) runs SIFT only on the frames that need it
  // (track_between_keyframes): features extracted ahead for every frame would be wasted.
  bool ExtractsLazily() const { return options_.track_between_keyframes; }
  // How many threads a frame's own work may use at once (default 1). With 2 or more and
  // track_between_keyframes, SIFT on a new keyframe and on the frame before it (for the
  // keyframe fusion) run side by side. Results are the same either way.
  void SetThreads(int threads);
  const SiftExtractor& extractor() const;
  const OdometryOptions& options() const { return options_; }
  const Calibration& calibration() const { return calib_; }
  // The motion model as used, one line: "6-DOF", or with "planar" the floor's normal and how it
  // was found (known once the first frame is processed).
  std::string MotionModelBrief() const;
  // With the planar model, once the first frame is processed: its level frame (planar_motion.hpp).
  const std::optional<Eigen::Matrix3d>& level_from_cam() const;
  // With gravity_correction: the readings taken, their mean weight and the largest tilt
  // between a frame and its reading, one line; "" without.
  std::string GravityBrief() const;

 private:
  // r (from the tracker, in the IR camera's frame) moved to the colour camera.
  FrameResult InColorCamera(FrameResult r) const;
  void CheckImageSize(const Frame& frame);

  cv::Size image_size_;  // the first frame's
  OdometryOptions options_;
  Calibration calib_;  // as used: without distortion unless options.undistort
  std::unique_ptr<Tracker> tracker_;
};

}  // namespace rgbdvo
