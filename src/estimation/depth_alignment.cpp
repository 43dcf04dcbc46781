#include "rgbdvo/estimation/depth_alignment.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>
#include <optional>
#include <stdexcept>
#include <tuple>

namespace rgbdvo {
namespace {

// Every `step`-th pixel (readings are not averaged across depth edges), no reading as NaN.
cv::Mat OdometryDepth(const cv::Mat& depth_m, int step) {
  cv::Mat d;
  cv::resize(depth_m, d, cv::Size(depth_m.cols / step, depth_m.rows / step), 0, 0,
             cv::INTER_NEAREST);
  d.setTo(std::numeric_limits<float>::quiet_NaN(), d <= 0);
  return d;
}

// One OpenCV odometry run between frames whose pyramids and normals the odometry has cached
// (prepareFrameCache, so several starts compute them once): compute(src, dst) gives Rt with
// p_dst = Rt * p_src (opencv2/rgbd/depth.hpp): src = current, dst = previous frame, so Rt =
// prev_from_cur; `start` is its initial value. No result when the odometry fails or returns
// non-finite numbers.
std::optional<Rigid3d> RunOdometry(const cv::rgbd::Odometry& odometry,
                                   cv::Ptr<cv::rgbd::OdometryFrame>& prev,
                                   cv::Ptr<cv::rgbd::OdometryFrame>& cur, const Rigid3d& start) {
  cv::Mat guess, Rt;
  cv::eigen2cv(Eigen::Matrix4d(start.matrix()), guess);
  if (!odometry.compute(cur, prev, Rt, guess) || Rt.empty()) return std::nullopt;
  Eigen::Matrix4d M;
  cv::cv2eigen(Rt, M);
  if (!M.allFinite()) return std::nullopt;
  Rigid3d T;
  T.matrix() = M;
  T.linear() = NearestRotation(T.linear());
  return T;
}

// Frames for one odometry (its own cache: FastICP's and ICP's pyramids differ). Neither uses
// the image's values; FastICP wants one of the right size.
std::pair<cv::Ptr<cv::rgbd::OdometryFrame>, cv::Ptr<cv::rgbd::OdometryFrame>> CachedFrames(
    const cv::rgbd::Odometry& odometry, const cv::Mat& prev_depth, const cv::Mat& cur_depth) {
  const cv::Mat image(cur_depth.size(), CV_8UC1, cv::Scalar(0));
  auto prev = cv::rgbd::OdometryFrame::create(image, prev_depth);
  auto cur = cv::rgbd::OdometryFrame::create(image, cur_depth);
  odometry.prepareFrameCache(prev, cv::rgbd::OdometryFrame::CACHE_DST);
  odometry.prepareFrameCache(cur, cv::rgbd::OdometryFrame::CACHE_SRC);
  return {prev, cur};
}

}  // namespace

void DepthAlignOptions::Check() const {
  if (!(max_translation_m > 0))
    throw std::invalid_argument("DepthAlignOptions.max_translation_m must be > 0");
  if (!(max_rotation_deg > 0 && max_rotation_deg <= 180))
    throw std::invalid_argument("DepthAlignOptions.max_rotation_deg must be in (0, 180]");
  if (!(min_agreement >= 0 && min_agreement <= 1))
    throw std::invalid_argument("DepthAlignOptions.min_agreement must be in [0, 1]");
  if (!(min_constraint >= 0 && min_constraint < 1))
    throw std::invalid_argument("DepthAlignOptions.min_constraint must be in [0, 1)");
  if (downsample < 1 || downsample > 8)
    throw std::invalid_argument("DepthAlignOptions.downsample must be in [1, 8]");
  if (!(agreement_sigmas > 0 && depth_noise_coeff >= 0 && agreement_floor_m >= 0))
    throw std::invalid_argument(
        "DepthAlignOptions.agreement_sigmas must be > 0, depth_noise_coeff and agreement_floor_m "
        ">= 0");
}

double DepthAgreement(const DepthAlignOptions& o, const Calibration& calib,
                      const cv::Mat& prev_depth_m, const cv::Mat& cur_depth_m,
                      const Rigid3d& prev_from_cur) {
  constexpr int kStep = 8;
  int landed = 0, agreed = 0;
  for (int v = kStep / 2; v < cur_depth_m.rows; v += kStep)
    for (int u = kStep / 2; u < cur_depth_m.cols; u += kStep) {
      const float z = cur_depth_m.at<float>(v, u);
      if (!(z > 0)) continue;
      const Eigen::Vector3d p = prev_from_cur * Eigen::Vector3d((u - calib.cx) * z / calib.fx,
                                                                (v - calib.cy) * z / calib.fy, z);
      if (!(p.z() > 0)) continue;
      const double pu = std::round(calib.fx * p.x() / p.z() + calib.cx);
      const double pv = std::round(calib.fy * p.y() / p.z() + calib.cy);
      if (!(pu >= 0 && pv >= 0 && pu < prev_depth_m.cols && pv < prev_depth_m.rows)) continue;
      const float reading = prev_depth_m.at<float>(static_cast<int>(pv), static_cast<int>(pu));
      if (!(reading > 0)) continue;
      ++landed;
      const double tolerance =
          o.agreement_sigmas * o.depth_noise_coeff * p.z() * p.z() + o.agreement_floor_m;
      if (std::abs(reading - p.z()) <= tolerance) ++agreed;
    }
  return landed > 0 ? static_cast<double>(agreed) / landed : 0.0;
}

TranslationConstraint MeasureTranslationConstraint(const cv::Mat& normals, double min_constraint) {
  TranslationConstraint c;
  if (normals.type() != CV_32FC3) return c;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  int n = 0;
  for (int v = 0; v < normals.rows; v += 2)
    for (int u = 0; u < normals.cols; u += 2) {
      const cv::Vec3f& m = normals.at<cv::Vec3f>(v, u);
      const Eigen::Vector3d normal(m[0], m[1], m[2]);
      if (!normal.allFinite() || !(normal.squaredNorm() > 0.5)) continue;
      scatter += normal * normal.transpose();
      ++n;
    }
  if (n == 0) {
    c.free_directions = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                         Eigen::Vector3d::UnitZ()};
    return c;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter / n);
  c.weakest = eigen.eigenvalues()(0);
  for (int k = 0; k < 3; ++k)
    if (eigen.eigenvalues()(k) < min_constraint)
      c.free_directions.push_back(eigen.eigenvectors().col(k));
  return c;
}

DepthAligner::DepthAligner(const DepthAlignOptions& options, const Calibration& calib)
    : options_(options), calib_(calib) {
  options_.Check();
  // The camera of the downsampled images: pixel k covers original pixels [s k, s k + s - 1].
  const double s = 1.0 / options.downsample;
  const cv::Mat K = (cv::Mat_<double>(3, 3) << calib.fx * s, 0, (calib.cx + 0.5) * s - 0.5, 0,
                     calib.fy * s, (calib.cy + 0.5) * s - 0.5, 0, 0, 1);
  icp_ = cv::rgbd::ICPOdometry::create(K);
  icp_->setMinDepth(calib.min_depth_m);
  icp_->setMaxDepth(calib.max_depth_m);
  icp_->setMaxTranslation(options.max_translation_m);
  icp_->setMaxRotation(options.max_rotation_deg);
  fast_ = cv::rgbd::FastICPOdometry::create(K);
}

DepthAlignResult DepthAligner::Align(const cv::Mat& prev_depth_m, const cv::Mat& cur_depth_m,
                                     const Rigid3d& prev_from_cur_guess) const {
  if (prev_depth_m.type() != CV_32FC1 || cur_depth_m.type() != CV_32FC1 ||
      prev_depth_m.size() != cur_depth_m.size() || prev_depth_m.empty())
    throw std::invalid_argument(
        "DepthAligner::Align needs two CV_32FC1 depth images of the same size");
  const cv::Mat prev = OdometryDepth(prev_depth_m, options_.downsample);
  const cv::Mat cur = OdometryDepth(cur_depth_m, options_.downsample);
  // The starts. FastICPOdometry from no motion finds the rotation of a fast turn well but, far
  // from the minimum, can trade a yaw for a sideways shift and end decimetres off; so ICP is
  // also started from its rotation with no translation and with the predicted one, and from the
  // prediction itself.
  std::vector<Rigid3d> candidates;
  cv::Ptr<cv::rgbd::OdometryFrame> icp_prev, icp_cur;  // not a structured binding: captured below
  std::tie(icp_prev, icp_cur) = CachedFrames(*icp_, prev, cur);
  const auto add_icp_from = [&](const Rigid3d& start) {
    if (const std::optional<Rigid3d> r = RunOdometry(*icp_, icp_prev, icp_cur, start))
      candidates.push_back(*r);
  };
  auto [fast_prev, fast_cur] = CachedFrames(*fast_, prev, cur);
  if (const std::optional<Rigid3d> f =
          RunOdometry(*fast_, fast_prev, fast_cur, Rigid3d::Identity())) {
    candidates.push_back(*f);
    add_icp_from(*f);
    Rigid3d turn = *f;
    turn.translation().setZero();
    add_icp_from(turn);
    turn.translation() = prev_from_cur_guess.translation();
    add_icp_from(turn);
  }
  add_icp_from(prev_from_cur_guess);

  DepthAlignResult result;
  if (candidates.empty()) {
    result.reason = "icp_failed";
    return result;
  }
  result.agreement = -1;
  for (const Rigid3d& T : candidates) {
    const double agreement = DepthAgreement(options_, calib_, prev_depth_m, cur_depth_m, T);
    if (agreement > result.agreement) {
      result.agreement = agreement;
      result.prev_from_cur = T;
    }
  }
  // Along a direction no surface faces, ICP's translation is whatever its start and noise made
  // it (on a floor with one wall, a slide of up to a metre along the wall): take the
  // prediction's there.
  result.constraint = MeasureTranslationConstraint(icp_prev->normals, options_.min_constraint);
  if (!result.constraint.free_directions.empty()) {
    Eigen::Vector3d t = result.prev_from_cur.translation();
    for (const Eigen::Vector3d& d : result.constraint.free_directions)
      t += d * d.dot(prev_from_cur_guess.translation() - t);
    result.prev_from_cur.translation() = t;
    result.agreement =
        DepthAgreement(options_, calib_, prev_depth_m, cur_depth_m, result.prev_from_cur);
  }
  const double angle_deg = Eigen::AngleAxisd(result.prev_from_cur.linear()).angle() * 180 / M_PI;
  if (result.prev_from_cur.translation().norm() > options_.max_translation_m ||
      angle_deg > options_.max_rotation_deg) {
    result.reason = "icp_too_large";
  } else if (result.agreement < options_.min_agreement) {
    result.reason = "icp_disagrees";
  } else {
    result.success = true;
  }
  return result;
}

}  // namespace rgbdvo
