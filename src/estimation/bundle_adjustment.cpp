#include "rgbdvo/estimation/bundle_adjustment.hpp"

#include <ceres/ceres.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>

namespace rgbdvo {

namespace {

// A pose block: cam_from_world as translation (3) then unit quaternion (x, y, z, w).
constexpr int kPoseSize = 7;
constexpr int kPoseTangent = 6;

Eigen::Matrix3d ExpRotation(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

void ToBlock(const Rigid3d& cam_from_world, double* block) {
  Eigen::Map<Eigen::Vector3d> translation(block);
  Eigen::Map<Eigen::Quaterniond> rotation(block + 3);
  translation = cam_from_world.translation();
  rotation = Eigen::Quaterniond(cam_from_world.linear()).normalized();
}

Rigid3d FromBlock(const double* block) {
  Rigid3d pose = Rigid3d::Identity();
  pose.linear() = Eigen::Map<const Eigen::Quaterniond>(block + 3).normalized().toRotationMatrix();
  pose.translation() = Eigen::Map<const Eigen::Vector3d>(block);
  return pose;
}

// The tangent space of a pose: delta = (translation, rotation) applied on the left,
// exp(delta) * pose. The cost functions give their derivatives in this tangent space directly
// (BundleResidual), in the first 6 of the block's 7 columns; so the Jacobian of Plus is the
// embedding [I; 0], and Ceres' product of the two is exactly the tangent derivative.
class PoseManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseSize; }
  int TangentSize() const override { return kPoseTangent; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const Rigid3d pose = FromBlock(x);
    Rigid3d moved = Rigid3d::Identity();
    moved.linear() = ExpRotation(Eigen::Map<const Eigen::Vector3d>(delta + 3));
    moved.translation() = Eigen::Map<const Eigen::Vector3d>(delta);
    ToBlock(moved * pose, x_plus_delta);
    return true;
  }
  bool PlusJacobian(const double* /*x*/, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, kPoseSize, kPoseTangent, Eigen::RowMajor>> j(jacobian);
    j.setZero();
    j.topRows<kPoseTangent>().setIdentity();
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    const Rigid3d py = FromBlock(y);
    const Rigid3d px = FromBlock(x);
    const Eigen::AngleAxisd turn(py.linear() * px.linear().transpose());
    const Eigen::Vector3d phi = turn.angle() * turn.axis();
    Eigen::Map<Eigen::Vector3d> rho(y_minus_x);
    Eigen::Map<Eigen::Vector3d> rotation(y_minus_x + 3);
    rotation = phi;
    rho = py.translation() - ExpRotation(phi) * px.translation();
    return true;
  }
  bool MinusJacobian(const double* /*x*/, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, kPoseTangent, kPoseSize, Eigen::RowMajor>> j(jacobian);
    j.setZero();
    j.leftCols<kPoseTangent>().setIdentity();
    return true;
  }
};

class ObservationCost : public ceres::SizedCostFunction<3, kPoseSize, 3> {
 public:
  ObservationCost(const BundleOptions& options, const BundleObservation& o)
      : options_(options), measured_(o.measured), depth_sigma_(o.depth_sigma) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Rigid3d cam_from_world = FromBlock(parameters[0]);
    const Eigen::Map<const Eigen::Vector3d> point(parameters[1]);
    if ((cam_from_world * point).z() <= 1e-6) return false;  // behind the camera: step refused
    Eigen::Matrix<double, 3, 6> d_pose;
    Eigen::Matrix3d d_point;
    const bool want = jacobians != nullptr;
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = BundleResidual(options_, cam_from_world, point, measured_, depth_sigma_,
                       want ? &d_pose : nullptr, want ? &d_point : nullptr);
    if (!want) return true;
    if (jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, kPoseSize, Eigen::RowMajor>> j(jacobians[0]);
      j.setZero();
      j.leftCols<kPoseTangent>() = d_pose;
    }
    if (jacobians[1] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> j(jacobians[1]);
      j = d_point;
    }
    return true;
  }

 private:
  BundleOptions options_;
  Eigen::Vector3d measured_;
  double depth_sigma_;
};

}  // namespace

Eigen::Vector3d BundleResidual(const BundleOptions& options, const Rigid3d& cam_from_world,
                               const Eigen::Vector3d& point, const Eigen::Vector3d& measured,
                               double depth_sigma, Eigen::Matrix<double, 3, 6>* d_pose,
                               Eigen::Matrix3d* d_point) {
  const Eigen::Vector3d q = cam_from_world * point;
  const double pixel_scale = options.focal_px / options.pixel_sigma;
  const double depth_scale =
      1.0 /
      (depth_sigma > 0 ? depth_sigma : options.depth_noise_coeff * measured.z() * measured.z());
  Eigen::Vector3d r(pixel_scale * (q.x() / q.z() - measured.x() / measured.z()),
                    pixel_scale * (q.y() / q.z() - measured.y() / measured.z()),
                    depth_scale * (q.z() - measured.z()));
  if (d_pose == nullptr && d_point == nullptr) return r;
  Eigen::Matrix3d d_q;  // dr / dq
  const double inv_z = 1.0 / q.z();
  d_q << pixel_scale * inv_z, 0, -pixel_scale * q.x() * inv_z * inv_z,  //
      0, pixel_scale * inv_z, -pixel_scale * q.y() * inv_z * inv_z,     //
      0, 0, depth_scale;
  // q = R p + t; after exp(delta) on the left, q' = exp(phi) q + rho: dq/drho = I,
  // dq/dphi = -[q]x.
  if (d_pose != nullptr) {
    d_pose->leftCols<3>() = d_q;
    d_pose->rightCols<3>() = -d_q * Skew(q);
  }
  if (d_point != nullptr) *d_point = d_q * cam_from_world.linear();
  return r;
}

BundleResult BundleAdjust(const BundleOptions& options, std::vector<BundleCamera>* cameras,
                          std::vector<Eigen::Vector3d>* points,
                          const std::vector<BundleObservation>& observations) {
  BundleResult result;
  if (observations.empty()) return result;
  std::vector<double> poses(cameras->size() * kPoseSize);
  for (size_t c = 0; c < cameras->size(); ++c)
    ToBlock((*cameras)[c].world_from_cam.inverse(), &poses[c * kPoseSize]);

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  PoseManifold manifold;
  ceres::HuberLoss huber(options.huber_sigmas);
  for (const BundleObservation& o : observations)
    problem.AddResidualBlock(new ObservationCost(options, o), &huber, &poses[o.camera * kPoseSize],
                             (*points)[o.point].data());
  for (size_t c = 0; c < cameras->size(); ++c) {
    double* block = &poses[c * kPoseSize];
    if (!problem.HasParameterBlock(block)) continue;
    problem.SetManifold(block, &manifold);
    if ((*cameras)[c].fixed) problem.SetParameterBlockConstant(block);
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;  // a window's few cameras: a small dense system
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  result.success = summary.IsSolutionUsable();
  result.iterations = static_cast<int>(summary.iterations.size());
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  if (!result.success) return result;
  for (size_t c = 0; c < cameras->size(); ++c)
    if (!(*cameras)[c].fixed)
      (*cameras)[c].world_from_cam = FromBlock(&poses[c * kPoseSize]).inverse();
  return result;
}

}  // namespace rgbdvo
