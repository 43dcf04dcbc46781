#include "motion_model.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/estimation/floor_plane.hpp"
#include "rgbdvo/estimation/planar_motion.hpp"

namespace rgbdvo {

MotionModelSetup SetUpMotionModel(const OdometryOptions& options, const Calibration& calib,
                                  const Frame& first) {
  MotionModelSetup model;
  std::ostringstream brief;
  if (!options.motion.planar()) {
    brief << "6-DOF";
    if (options.gravity_correction)
      brief << ", roll and pitch pulled toward the accelerometer's gravity (time constant "
            << options.gravity.time_constant_s << " s)";
    model.brief = brief.str();
    return model;
  }
  brief << std::fixed << std::setprecision(1) << "planar (x, z and yaw about the floor's normal)";
  const MotionOptions& m = options.motion;
  if (m.floor == FloorSource::kGiven) {
    model.level_from_cam =
        LevelFromFloorNormal(FloorNormalFromMount(m.mount_pitch_deg, m.mount_roll_deg));
    brief << ", mount given: pitch " << m.mount_pitch_deg << " deg, roll " << m.mount_roll_deg
          << " deg";
  } else if (m.floor == FloorSource::kAccelerometer) {
    if (!first.gravity_in_cam)
      throw std::runtime_error("--motion planar --floor accelerometer: frame " +
                               std::to_string(first.index) +
                               " has no accelerometer reading; use --floor depth or given");
    const Eigen::Vector3d normal = first.gravity_in_cam->normalized();
    model.level_from_cam = LevelFromFloorNormal(normal);
    const Eigen::Vector2d mount = MountFromFloorNormal(normal);
    brief << ", floor's normal from frame " << first.index << "'s accelerometer reading: pitch "
          << mount.x() << " deg, roll " << mount.y() << " deg (|a| " << std::setprecision(2)
          << first.gravity_in_cam->norm() << " m/s^2)";
  } else {
    Rng rng(options.seed);
    const FloorFit fit = FitFloor(FloorFitOptions{}, calib, first.depth_m, rng);
    if (!fit.success)
      throw std::runtime_error("--motion planar: no floor in the first frame's depth image (" +
                               fit.reason +
                               "); start with the floor in view, take it from the "
                               "accelerometer (--floor accelerometer) or give the camera's mount "
                               "with --floor given --mount-pitch DEG --mount-roll DEG");
    model.level_from_cam = fit.level_from_cam;
    brief << ", floor fitted in frame " << first.index << "'s depth: " << fit.Brief();
  }
  model.brief = brief.str();
  return model;
}

}  // namespace rgbdvo
