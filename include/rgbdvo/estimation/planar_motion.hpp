#pragma once
// The motion of a camera rigidly mounted on a robot that drives on a plane: the paper's 3-DOF
// case (section 3: "one could obtain better accuracy if the pose estimates were limited to
// indoor robot cases where the motion could be limited to a 3-DOF case"). In the camera's level
// frame (the camera frame turned by its roll and pitch against the floor, so that its y axis is
// the floor's normal, pointing down) the motion is a turn about y (yaw) and a translation in
// x-z; the camera's height does not change.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "rgbdvo/estimation/point_pair.hpp"
#include "rgbdvo/estimation/ransac.hpp"
#include "rgbdvo/geometry/geometry.hpp"

namespace rgbdvo {

// prev_from_cur in the camera frame of the planar motion (yaw_rad about the level frame's y,
// then the translation (x_m, 0, z_m) in the level frame): level_from_cam^T T level_from_cam.
Rigid3d PlanarMotion(const Eigen::Matrix3d& level_from_cam, double yaw_rad, double x_m, double z_m);

// The level frame of a camera whose floor has unit normal `normal_in_cam` (pointing down, away
// from the camera): the smallest rotation taking it to +y. (Any turn about y gives the same
// planar motions.)
Eigen::Matrix3d LevelFromFloorNormal(const Eigen::Vector3d& normal_in_cam);

// The floor's unit normal in the camera frame for a camera mounted with this pitch (positive:
// looking down) and roll (positive: the normal leans to the camera's +x), degrees; the angles
// FloorFit reports: normal = (sin roll, cos roll cos pitch, cos roll sin pitch).
Eigen::Vector3d FloorNormalFromMount(double pitch_deg, double roll_deg);
// The inverse, degrees: pitch = atan2(n_z, n_y), roll = asin(n_x), for a unit normal.
Eigen::Vector2d MountFromFloorNormal(const Eigen::Vector3d& normal_in_cam);  // (pitch, roll)

// The planar motion nearest to prev_from_cur: its turn about the level frame's y (the yaw of
// its rotation's projection onto such turns) and its translation's x-z part in the level frame.
// Used for estimates made with all 6 degrees of freedom (the depth images' ICP).
Rigid3d ProjectPlanar(const Eigen::Matrix3d& level_from_cam, const Rigid3d& prev_from_cur);

// The planar motion minimising sum |a_k - (R b_k + t)|^2 over the x-z coordinates in the level
// frame (a = p_prev, b = p_cur; heights are not compared) of the pairs named by `indices` (all
// when empty): the 2D Kabsch solution, yaw = atan2(sum a'_x b'_z - a'_z b'_x, sum a'.b') on the
// centred points. Two pairs determine it (the minimal sample). nullopt for fewer than 2 pairs or
// pairs whose x-z positions coincide.
std::optional<Rigid3d> AlignPlanar(const Eigen::Matrix3d& level_from_cam,
                                   const std::vector<PointPair>& pairs,
                                   const std::vector<int>& indices = {});

// RANSAC over 2-pair planar hypotheses (EstimateRansac with AlignPlanar): inliers by the full
// 3D distance (a pair whose heights disagree is an outlier too), refined by AlignPlanar.
RansacResult EstimatePlanarRansac(const RansacOptions& options,
                                  const Eigen::Matrix3d& level_from_cam,
                                  const std::vector<PointPair>& pairs, Rng& rng);

}  // namespace rgbdvo
