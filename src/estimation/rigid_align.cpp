#include "rgbdvo/estimation/rigid_align.hpp"

#include <Eigen/SVD>

namespace rgbdvo {

std::optional<Rigid3d> AlignRigid(const std::vector<PointPair>& pairs,
                                  const std::vector<int>& indices) {
  const size_t n = indices.empty() ? pairs.size() : indices.size();
  if (n < 3) return std::nullopt;
  auto at = [&](size_t k) -> const PointPair& {
    return indices.empty() ? pairs[k] : pairs[indices[k]];
  };

  Eigen::Vector3d c_prev = Eigen::Vector3d::Zero(), c_cur = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < n; ++k) {
    c_prev += at(k).p_prev;
    c_cur += at(k).p_cur;
  }
  c_prev /= static_cast<double>(n);
  c_cur /= static_cast<double>(n);

  // Paper eq. 5: cross-covariance of the centred point sets (cur as I, prev as J).
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (size_t k = 0; k < n; ++k) H += (at(k).p_cur - c_cur) * (at(k).p_prev - c_prev).transpose();

  // Eq. 7-10: H = U S V^T, R = V U^T maximises tr(R H). A reflection (det = -1) is turned into
  // the best proper rotation by flipping the axis of the smallest singular value (Umeyama 1991).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& s = svd.singularValues();
  if (!(s(0) > 0) || s(1) < 1e-9 * s(0)) return std::nullopt;  // coincident or collinear points
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0) S(2, 2) = -1;
  Rigid3d prev_from_cur = Rigid3d::Identity();
  prev_from_cur.linear() = svd.matrixV() * S * svd.matrixU().transpose();
  prev_from_cur.translation() = c_prev - prev_from_cur.linear() * c_cur;
  return prev_from_cur;
}

}  // namespace rgbdvo
