#pragma once
// The tracking policy behind Odometry (private to src/odometry): which reference a frame is
// measured against, when the keyframe is renewed, and what happens when the features fail.

#include <memory>
#include <optional>
#include <string>

#include "local_map.hpp"
#include "motion_measurer.hpp"
#include "reference.hpp"
#include "rgbdvo/estimation/depth_alignment.hpp"
#include "rgbdvo/estimation/motion_estimate.hpp"
#include "rgbdvo/odometry/gravity_correction.hpp"
#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo {

// Track runs a frame through these stages, in the IR camera's frame:
//   begin: the constant-velocity prior, the frame lifted (and its tracking pyramid made);
//   start: until the first reference, a frame that can be one becomes it;
//   measure: the keyframe's keypoints tracked into the frame; else SIFT matched against the
//            keyframe; else against the last estimated frame, which becomes the keyframe;
//   accept: the keyframe decision, its pose measured again by matches and fused with the last
//           frame's, the frame becomes the last estimated one;
//   align depth: where no features verified, the depth images aligned;
//   give up: the frame predicted (or held), and after a run of them a restart from it.
class Tracker {
 public:
  // options must have passed Check(); calib as the odometry uses it.
  Tracker(const OdometryOptions& options, const Calibration& calib);
  // The frame's pose and velocity in the IR camera's frame; features nullopt when SIFT is to run
  // only where needed (track_between_keyframes). The frame by value: a frame handed over keeps
  // its depth image without a copy (Odometry::Process).
  FrameResult Track(Frame frame, std::optional<Features> features);

  void SetThreads(int threads) { measurer_.SetThreads(threads); }
  const SiftExtractor& extractor() const { return measurer_.extractor(); }
  const std::string& MotionModelBrief() const { return motion_brief_; }
  const std::optional<Eigen::Matrix3d>& level_from_cam() const { return level_from_cam_; }
  std::string GravityBrief() const;

 private:
  enum class Phase { kNoReference, kRunning };
  // How the keyframe's next frames are measured: by its keypoints tracked into them, or by SIFT
  // matching once a frame's tracks failed where SIFT still reached the keyframe.
  enum class KeyframeUse { kTrack, kMatch };
  // What verified the current frame's motion.
  enum class Measured { kNothing, kTracks, kKeyframeMatches, kLastFrameMatches };

  // The frame as it goes through the stages.
  struct Current {
    FrameResult r;
    Rigid3d world_from_pred = Rigid3d::Identity();  // the constant-velocity prior
    Reference ref;                                  // the frame as a reference
    MotionEstimate motion;                          // ref_from_cur of the kept estimate
    Measured measured = Measured::kNothing;
    bool tracks_failed = false;  // its keypoints were tracked and failed verification
    // The kept estimate's inliers, when it is SIFT matches against the keyframe (for the map).
    KeyframeMatches keyframe_matches;
  };

  // Stages (see the class comment).
  Current Begin(const Frame& frame, std::optional<Features> features);
  FrameResult Start(const Frame& frame, Current* c);
  void Measure(Current* c);
  FrameResult Accept(const Frame& frame, Current* c);
  bool AlignDepth(const Frame& frame, Current* c);
  FrameResult GiveUp(Current* c);

  // Helpers of the stages.
  Rigid3d DepthFromColor(const Frame& frame) const;
  Reference MakeReference(const Frame& frame, std::optional<Features> features,
                          const Rigid3d& depth_from_color, FrameResult* r);
  void EnsureCurrentFeatures(Current* c);
  bool CanBeReference(Current* c);
  bool DepthToAlign(const Frame& frame) const;
  MotionEstimate TrackFromKeyframe(Current* c);
  bool DecideKeyframe(Current* c);
  MotionEstimate MeasureAside(const Reference& ref, Current* c, FrameResult* aside,
                              std::string* reason);
  void FuseWithLastFrame(Current* c);

  // Makes cur (now at its world_from_cam) the last estimated frame, and the keyframe with
  // new_keyframe. The velocity is measured from `measured_from` (its pose and time) to cur.
  void Advance(Reference cur, bool new_keyframe, const Reference& measured_from);
  // Both references become `ref` (the first reference, a restart), the map's only keyframe.
  void Restart(Reference ref);
  // With the local map: the new keyframe into it (with its matches to the keyframe before),
  // adjusted with the keyframes sharing its points; every pose the next frames are chained
  // from moves with it.
  void AdjustWithMap(const KeyframeMatches& matches, FrameResult* r);
  // With gravity_correction and a reading: turns the last estimated frame, and every pose the
  // next frames are chained from, toward the reading's down (GravityCorrection).
  void CorrectTilt(const Frame& frame);
  // True when the velocity base lies before last_ in colour time: a velocity to predict with.
  bool Moving() const;
  // From the velocity base to last_, per second of colour time (zero without both).
  Velocity LastVelocity() const;

  OdometryOptions options_;
  Calibration calib_;
  MotionMeasurer measurer_;
  std::unique_ptr<DepthAligner> depth_aligner_;    // with depth_fallback
  std::optional<Eigen::Matrix3d> level_from_cam_;  // with the planar model
  std::optional<GravityCorrection> gravity_;       // with gravity_correction
  std::unique_ptr<LocalMap> map_;                  // with local_map (6-DOF, no gravity)
  std::string motion_brief_;

  Phase phase_ = Phase::kNoReference;
  Reference key_;  // what frames are measured against
  KeyframeUse key_use_ = KeyframeUse::kTrack;
  Reference last_;  // the last estimated frame (fallback when the keyframe fails)
  VelocityBase before_;
  int rejected_run_ = 0;
  DepthKeyframe depth_key_;
};

}  // namespace rgbdvo
