#include "rgbdvo/odometry.hpp"

#include <chrono>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/point_pairs.hpp"

namespace rgbdvo {
namespace {

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void OdometryOptions::Check() const {
  features.Check();
  matching.Check();
  ransac.Check();
  verify.Check();
  if (max_rejected_run < 0) throw std::invalid_argument("max_rejected_run must be >= 0");
}

std::string OdometryOptions::ToString() const {
  std::ostringstream s;
  s << "features.max_features = " << features.max_features << "\n"
    << "features.octave_layers = " << features.octave_layers << "\n"
    << "features.contrast_threshold = " << features.contrast_threshold << "\n"
    << "features.edge_threshold = " << features.edge_threshold << "\n"
    << "features.sigma = " << features.sigma << "\n"
    << "matching.ratio = " << matching.ratio << "\n"
    << "matching.mutual = " << (matching.mutual ? "true" : "false") << "\n"
    << "ransac.max_trials = " << ransac.max_trials << "\n"
    << "ransac.sample_size = " << ransac.sample_size << "\n"
    << "ransac.inlier_distance_m = " << ransac.inlier_distance_m << "\n"
    << "verify.min_inliers = " << verify.min_inliers << "\n"
    << "verify.max_translation_m = " << verify.max_translation_m << "\n"
    << "verify.max_rotation_deg = " << verify.max_rotation_deg << "\n"
    << "max_rejected_run = " << max_rejected_run << "\n"
    << "seed = " << seed << "\n";
  return s.str();
}

std::string FrameResult::StatusString() const {
  switch (status) {
    case FrameStatus::kFirst: return "first";
    case FrameStatus::kAccepted: return "accepted";
    case FrameStatus::kRejected: return "rejected:" + reason;
    case FrameStatus::kLost: return "lost:" + reason;
  }
  return "unknown";
}

Odometry::Odometry(const OdometryOptions& options, const Calibration& calib)
    : options_(options), calib_(calib), extractor_(options.features), rng_(options.seed) {
  options_.Check();
  calib_.Check();
}

FrameResult Odometry::Process(const Frame& frame) {
  FrameResult r;
  r.frame = frame.index;
  r.timestamp = frame.timestamp;

  auto t0 = std::chrono::steady_clock::now();
  Features features = extractor_.Extract(frame.bgr);
  r.times.features = Since(t0);
  r.features = static_cast<int>(features.size());

  if (!has_reference_) {
    has_reference_ = true;
    ref_features_ = std::move(features);
    ref_depth_ = frame.depth_m;
    r.world_from_cam = world_from_ref_;
    r.status = FrameStatus::kFirst;
    return r;
  }

  t0 = std::chrono::steady_clock::now();
  const std::vector<cv::DMatch> matches = MatchFeatures(options_.matching, ref_features_, features);
  r.times.matching = Since(t0);
  r.matches = static_cast<int>(matches.size());

  t0 = std::chrono::steady_clock::now();
  const std::vector<PointPair> pairs =
      LiftMatches(calib_, ref_depth_, frame.depth_m, ref_features_, features, matches);
  r.times.lifting = Since(t0);
  r.pairs = static_cast<int>(pairs.size());

  t0 = std::chrono::steady_clock::now();
  const RansacResult ransac = EstimateRigidRansac(options_.ransac, pairs, rng_);
  r.times.ransac = Since(t0);
  r.inliers = static_cast<int>(ransac.inliers.size());

  r.reason = CheckMotion(options_.verify, ransac);
  if (r.reason.empty()) {
    // world_from_cur = world_from_ref * ref_from_cur; the current frame becomes the reference.
    world_from_ref_ = world_from_ref_ * ransac.prev_from_cur;
    world_from_ref_.linear() = NearestRotation(world_from_ref_.linear());
    ref_features_ = std::move(features);
    ref_depth_ = frame.depth_m;
    rejected_run_ = 0;
    r.status = FrameStatus::kAccepted;
  } else if (options_.max_rejected_run > 0 && ++rejected_run_ >= options_.max_rejected_run) {
    // The reference is out of reach: restart from this frame at the last known pose.
    ref_features_ = std::move(features);
    ref_depth_ = frame.depth_m;
    rejected_run_ = 0;
    r.status = FrameStatus::kLost;
  } else {
    r.status = FrameStatus::kRejected;
  }
  r.world_from_cam = world_from_ref_;
  return r;
}

}  // namespace rgbdvo
