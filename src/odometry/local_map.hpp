#pragma once
// The local map (private to src/odometry): the keyframes' keypoints as 3D points seen again by
// later keyframes, and bundle adjustment of the keyframes that share them
// (docs/decisions/0048-local-map.md).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <utility>
#include <vector>

#include "reference.hpp"
#include "rgbdvo/estimation/bundle_adjustment.hpp"
#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

// A new keyframe's verified SIFT matches to the keyframe before it: (that keyframe's keypoint,
// the new one's), the inliers of the estimate that placed it.
struct KeyframeMatches {
  int keyframe_frame = -1;  // the frame number of the keyframe matched against
  std::vector<std::pair<int, int>> pairs;
};

class LocalMap {
 public:
  // focal_px: the depth camera's focal length (the residuals in pixels).
  LocalMap(const OdometryOptions& options, const Calibration& calib);

  // Adds a new keyframe (with its features and their 3D points) at key.world_from_cam: the map
  // points of the keyframe before that `matches` pair with its keypoints, then each other map
  // point it sees near where the point projects, by descriptor, gain an observation; its other
  // keypoints with a 3D point become map points. Then the keyframes sharing the most points
  // with it are adjusted with the points they see. Returns the keyframe's adjusted pose.
  Rigid3d AddKeyframe(const Reference& key, const KeyframeMatches& matches = {});
  // Forgets everything (a restart: the new reference's pose is only a prediction).
  void Clear();

  size_t keyframes() const { return keyframes_.size(); }
  size_t points() const { return points_.size(); }

 private:
  struct Observation {
    int64_t keyframe = 0;      // the keyframe's id
    Eigen::Vector3d measured;  // the keypoint's 3D point in that keyframe's camera
    double depth_sigma = 0;    // its depth's, m (DepthSigmas)
  };
  struct MapPoint {
    Eigen::Vector3d world;
    std::array<uint8_t, 128> descriptor;  // the last observing keypoint's SIFT descriptor
    int64_t first_keyframe = 0;
    std::vector<Observation> observations;
  };
  struct Keyframe {
    int64_t id = 0;
    int frame = -1;
    Rigid3d world_from_cam;
    std::vector<int64_t> points;             // the map points it observes
    std::vector<int64_t> point_of_keypoint;  // the map point each keypoint observes, or -1
  };

  // The sigma of each keypoint's depth: the Kinect's noise, and the depth's change over the
  // keypoint's localisation noise (a slope or an edge under the keypoint).
  std::vector<double> DepthSigmas(const Reference& key) const;
  // The map points of the newest keyframe that `matches` pair with key's keypoints (map point
  // id -> keypoint).
  std::map<int64_t, int> FromMatches(const Reference& key, const KeyframeMatches& matches) const;
  // Adds to `seen` the other map points key sees, by projection and descriptor, each as a
  // keypoint not yet in `seen`.
  void Associate(const Reference& key, std::map<int64_t, int>* seen) const;
  // The keyframes adjusted with the newest: those sharing the most points with it.
  std::vector<int64_t> Window() const;
  void Adjust(const std::vector<int64_t>& window);
  // Points seen by one keyframe only once a few more came; the oldest keyframe beyond the bound.
  void Cull();
  void RemoveOldestKeyframe();
  Keyframe* Find(int64_t id);

  OdometryOptions options_;
  Calibration calib_;
  BundleOptions bundle_;
  std::deque<Keyframe> keyframes_;  // oldest first
  std::map<int64_t, MapPoint> points_;
  int64_t next_keyframe_ = 0;
  int64_t next_point_ = 0;
};

}  // namespace rgbdvo
