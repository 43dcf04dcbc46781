#include "rgbdvo/odometry/odometry.hpp"

#include <cmath>
#include <stdexcept>

#include "rgbdvo/odometry/odometry_parameters.hpp"
#include "rgbdvo/sensor/camera.hpp"
#include "rgbdvo/util/stopwatch.hpp"
#include "tracker.hpp"

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
  gravity.Check();
  tracking.Check();
  local_map.Check();
  if (!(track_stale_noise_ratio == 0 || track_stale_noise_ratio >= 1))
    throw std::invalid_argument(
        "OdometryOptions.track_stale_noise_ratio must be >= 1 (or 0 = no such keyframes)");
  if (gravity_correction && motion.planar())
    throw std::invalid_argument(
        "OdometryOptions.gravity_correction corrects roll and pitch, which motion planar holds "
        "fixed: use one or the other");
  if (!(std::abs(motion.mount_pitch_deg) < 90 && std::abs(motion.mount_roll_deg) < 90))
    throw std::invalid_argument(
        "OdometryOptions.motion.mount_pitch_deg and mount_roll_deg must be within (-90, 90)");
}

void LocalMapOptions::Check() const {
  if (window_keyframes < 2 || window_keyframes > 100)
    throw std::invalid_argument("LocalMapOptions.window_keyframes must be in [2, 100]");
  if (max_keyframes < window_keyframes || max_keyframes > 1000)
    throw std::invalid_argument(
        "LocalMapOptions.max_keyframes must be in [window_keyframes, 1000]");
  if (!(search_radius_px > 0 && search_radius_px <= 100))
    throw std::invalid_argument("LocalMapOptions.search_radius_px must be in (0, 100]");
  if (max_iterations < 1 || max_iterations > 1000)
    throw std::invalid_argument("LocalMapOptions.max_iterations must be in [1, 1000]");
}

OdometryOptions PresetOptions(const std::string& name) {
  OdometryOptions o;
  if (name == "default") return o;
  if (name == "paper") {
    o.features = FeatureOptions::Lowe();  // Lowe's SIFT, as cv::SIFT's defaults
    o.features.implementation =
        SiftImplementation::kOpenCv;     // a reference SIFT (the paper names none)
    o.matching.mutual = false;           // the paper names no matching rule; a plain ratio test
    o.refine_enabled = false;            // SVD on the inliers only (eq. 5-10)
    o.keyframe_inlier_ratio = 0;         // successive frames
    o.fuse_keyframe_pose = false;        // one estimate per frame
    o.ransac.confidence = 0;             // always 200 trials
    o.undistort = false;                 // "a perfect pinhole model was used"
    o.lifting.max_depth_jump_ratio = 0;  // depth at the nearest pixel
    o.guided_radius_px = 0;              // brute-force matching
    o.guided_rematch = false;            // (no prior to correct)
    o.predict_failed_frames = false;     // a rejected frame keeps the last pose
    o.depth_fallback = false;            // features only
    o.depth_keyframe = false;            // (with the fallback) frame to frame
    o.compensate_depth_delay = false;    // depth at the keypoint's own pixel
    o.depth_term_step = 0;               // feature residuals only
    o.track_between_keyframes = false;   // SIFT and matching on every frame
    o.local_map.enabled = false;         // frame to frame only
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
    : options_(options), calib_(calib) {
  options_.Check();
  calib_.Check();
  if (!options_.undistort) calib_.dist_ir = {0, 0, 0, 0, 0};
  tracker_ = std::make_unique<Tracker>(options_, calib_);
}

Odometry::~Odometry() = default;

void Odometry::CheckImageSize(const Frame& frame) {
  const cv::Size size = frame.bgr.size();
  const auto text = [](const cv::Size& s) {
    return std::to_string(s.width) + "x" + std::to_string(s.height);
  };
  const std::string where =
      frame.name.empty() ? "frame " + std::to_string(frame.index) : frame.name;
  if (size.empty()) throw std::runtime_error(where + ": empty image");
  if (size.width < kMinImageSize.width || size.height < kMinImageSize.height)
    throw std::runtime_error(where + ": image " + text(size) +
                             " is too small to process (at least " + text(kMinImageSize) +
                             " pixels)");
  if (image_size_.empty()) image_size_ = size;
  if (size != image_size_)
    throw std::runtime_error(where + ": image " + text(size) + ", but the first frame's is " +
                             text(image_size_) + " (a recording's images are all one size)");
}

FrameResult Odometry::Process(Frame frame) {
  CheckImageSize(frame);
  if (ExtractsLazily()) return InColorCamera(tracker_->Track(std::move(frame), std::nullopt));
  const Stopwatch t0;
  Features features = extractor().Extract(frame.bgr);
  const double seconds = t0.Seconds();
  FrameResult r = Process(std::move(frame), std::move(features));
  r.times.features = seconds;
  return r;
}

FrameResult Odometry::Process(Frame frame, Features features) {
  CheckImageSize(frame);
  return InColorCamera(tracker_->Track(std::move(frame), std::move(features)));
}

void Odometry::SetThreads(int threads) { tracker_->SetThreads(threads); }

const SiftExtractor& Odometry::extractor() const { return tracker_->extractor(); }

std::string Odometry::MotionModelBrief() const { return tracker_->MotionModelBrief(); }

const std::optional<Eigen::Matrix3d>& Odometry::level_from_cam() const {
  return tracker_->level_from_cam();
}

std::string Odometry::GravityBrief() const { return tracker_->GravityBrief(); }

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

}  // namespace rgbdvo
