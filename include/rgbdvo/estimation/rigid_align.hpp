#pragma once
// Least-squares rigid alignment of 3D point pairs (paper eq. 5-10; Arun et al. 1987, Horn 1987).

#include <optional>
#include <vector>

#include "rgbdvo/estimation/point_pair.hpp"
#include "rgbdvo/geometry/geometry.hpp"

namespace rgbdvo {

// Returns prev_from_cur = (R, t) minimising sum_k |p_prev_k - (R p_cur_k + t)|^2 over the pairs
// named by `indices` (all pairs when empty): R from the SVD of the centred cross-covariance with
// the reflection case (det = -1) corrected, t from the centroids. nullopt for fewer than 3 pairs
// or a degenerate (collinear) configuration.
std::optional<Rigid3d> AlignRigid(const std::vector<PointPair>& pairs,
                                  const std::vector<int>& indices = {});

}  // namespace rgbdvo
