#include "local_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "rgbdvo/sensor/camera.hpp"

namespace rgbdvo {

namespace {

constexpr int kDescriptorBytes = 128;  // SIFT

int DescriptorDistance(const uint8_t* a, const uint8_t* b) {
  int sum = 0;
  for (int k = 0; k < kDescriptorBytes; ++k) {
    const int d = static_cast<int>(a[k]) - static_cast<int>(b[k]);
    sum += d * d;
  }
  return sum;
}

int64_t CellKey(double u, double v, double cell) {
  const auto cu = static_cast<int64_t>(std::floor(u / cell));
  const auto cv = static_cast<int64_t>(std::floor(v / cell));
  return static_cast<int64_t>((static_cast<uint64_t>(cu) << 32) ^
                              static_cast<uint64_t>(static_cast<uint32_t>(cv)));
}

}  // namespace

LocalMap::LocalMap(const OdometryOptions& options, const Calibration& calib)
    : options_(options), calib_(calib) {
  bundle_.focal_px = 0.5 * (calib.fx + calib.fy);
  bundle_.pixel_sigma = options.refine.pixel_sigma;
  bundle_.depth_noise_coeff = options.refine.depth_noise_coeff;
  bundle_.huber_sigmas = options.refine.huber_sigmas;
  bundle_.max_iterations = options.local_map.max_iterations;
}

void LocalMap::Clear() {
  keyframes_.clear();
  points_.clear();
}

Rigid3d LocalMap::AddKeyframe(const Reference& key, const KeyframeMatches& matches) {
  if (key.features.descriptors.cols != kDescriptorBytes || key.features.descriptors.type() != CV_8U)
    throw std::invalid_argument("LocalMap: SIFT descriptors expected (128 bytes each)");
  Keyframe kf;
  kf.id = next_keyframe_++;
  kf.frame = key.frame;
  kf.world_from_cam = key.world_from_cam;
  kf.point_of_keypoint.assign(key.points.size(), -1);
  std::map<int64_t, int> seen = FromMatches(key, matches);
  Associate(key, &seen);
  const std::vector<double> depth_sigmas = DepthSigmas(key);
  std::vector<bool> used(key.points.size(), false);
  for (const auto& [id, i] : seen) {
    MapPoint& p = points_.at(id);
    p.observations.push_back({kf.id, *key.points[i], depth_sigmas[i]});
    std::copy_n(key.features.descriptors.ptr<uint8_t>(i), kDescriptorBytes, p.descriptor.begin());
    kf.points.push_back(id);
    kf.point_of_keypoint[i] = id;
    used[i] = true;
  }
  for (size_t i = 0; i < key.points.size(); ++i) {
    if (!key.points[i] || used[i]) continue;
    MapPoint p;
    p.world = key.world_from_cam * *key.points[i];
    std::copy_n(key.features.descriptors.ptr<uint8_t>(static_cast<int>(i)), kDescriptorBytes,
                p.descriptor.begin());
    p.first_keyframe = kf.id;
    p.observations.push_back({kf.id, *key.points[i], depth_sigmas[i]});
    kf.points.push_back(next_point_);
    kf.point_of_keypoint[i] = next_point_;
    points_.emplace(next_point_++, std::move(p));
  }
  keyframes_.push_back(std::move(kf));
  const std::vector<int64_t> window = Window();
  if (window.size() >= 2) Adjust(window);
  Rigid3d adjusted = keyframes_.back().world_from_cam;
  Cull();
  return adjusted;
}

std::vector<double> LocalMap::DepthSigmas(const Reference& key) const {
  std::vector<double> sigmas(key.points.size(), 0.0);
  const cv::Mat& depth = key.depth_m;
  for (size_t i = 0; i < key.points.size(); ++i) {
    if (!key.points[i]) continue;
    const double z = key.points[i]->z();
    const double kinect = bundle_.depth_noise_coeff * z * z;
    sigmas[i] = kinect;
    if (depth.empty()) continue;
    const cv::Point2f& pt = key.features.keypoints[i].pt;
    const Eigen::Vector2d ir = ColorToIr(calib_, Eigen::Vector2d(pt.x, pt.y), z);
    const int x = static_cast<int>(std::lround(ir.x()));
    const int y = static_cast<int>(std::lround(ir.y()));
    if (x < 1 || y < 1 || x + 1 >= depth.cols || y + 1 >= depth.rows) continue;
    const float l = depth.at<float>(y, x - 1), r = depth.at<float>(y, x + 1);
    const float u = depth.at<float>(y - 1, x), d = depth.at<float>(y + 1, x);
    if (!(l > 0 && r > 0 && u > 0 && d > 0)) continue;
    const double slope = std::hypot(0.5 * (r - l), 0.5 * (d - u));  // m per depth pixel
    sigmas[i] = std::hypot(kinect, slope * bundle_.pixel_sigma);
  }
  return sigmas;
}

std::map<int64_t, int> LocalMap::FromMatches(const Reference& key,
                                             const KeyframeMatches& matches) const {
  std::map<int64_t, int> seen;
  if (keyframes_.empty() || keyframes_.back().frame != matches.keyframe_frame) return seen;
  const Keyframe& before = keyframes_.back();
  std::set<int> taken;
  for (const auto& [from, to] : matches.pairs) {
    if (from < 0 || static_cast<size_t>(from) >= before.point_of_keypoint.size()) continue;
    if (to < 0 || static_cast<size_t>(to) >= key.points.size() || !key.points[to]) continue;
    const int64_t id = before.point_of_keypoint[from];
    if (id < 0 || points_.count(id) == 0 || seen.count(id) > 0 || !taken.insert(to).second)
      continue;
    seen[id] = to;
  }
  return seen;
}

void LocalMap::Associate(const Reference& key, std::map<int64_t, int>* seen) const {
  // Where a map point projects, the keypoints within the search radius whose depth agrees as
  // closely as the radius allows sideways (plus the depth noise); the nearest descriptor wins
  // if it passes the ratio test, and a keypoint keeps the map point nearest to it in descriptor.
  const double f = bundle_.focal_px;
  const double radius = options_.local_map.search_radius_px;
  std::unordered_map<int64_t, std::vector<int>> grid;
  for (size_t i = 0; i < key.points.size(); ++i) {
    if (!key.points[i]) continue;
    const Eigen::Vector3d& p = *key.points[i];
    grid[CellKey(f * p.x() / p.z(), f * p.y() / p.z(), radius)].push_back(static_cast<int>(i));
  }
  const double ratio2 = options_.matching.ratio * options_.matching.ratio;
  const Rigid3d cam_from_world = key.world_from_cam.inverse();
  std::vector<std::pair<int, int64_t>> best_of_keypoint(key.points.size(),
                                                        {std::numeric_limits<int>::max(), -1});
  std::vector<bool> taken(key.points.size(), false);
  for (const auto& [id, i] : *seen) taken[i] = true;
  for (const auto& [id, point] : points_) {
    if (seen->count(id) > 0) continue;
    const Eigen::Vector3d q = cam_from_world * point.world;
    if (q.z() <= 0) continue;
    const double u = f * q.x() / q.z();
    const double v = f * q.y() / q.z();
    const double depth_tolerance = radius / f * q.z() + options_.refine.inlier_sigmas *
                                                            bundle_.depth_noise_coeff * q.z() *
                                                            q.z();
    int best = std::numeric_limits<int>::max(), second = best, best_i = -1;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const auto cell = grid.find(CellKey(u + dx * radius, v + dy * radius, radius));
        if (cell == grid.end()) continue;
        for (const int i : cell->second) {
          if (taken[i]) continue;
          const Eigen::Vector3d& p = *key.points[i];
          const double du = f * p.x() / p.z() - u;
          const double dv = f * p.y() / p.z() - v;
          if (du * du + dv * dv > radius * radius || std::abs(p.z() - q.z()) > depth_tolerance)
            continue;
          const int d =
              DescriptorDistance(key.features.descriptors.ptr<uint8_t>(i), point.descriptor.data());
          if (d < best) {
            second = best;
            best = d;
            best_i = i;
          } else if (d < second) {
            second = d;
          }
        }
      }
    }
    if (best_i < 0 || !(best < ratio2 * second)) continue;
    if (best < best_of_keypoint[best_i].first) best_of_keypoint[best_i] = {best, id};
  }
  for (size_t i = 0; i < best_of_keypoint.size(); ++i)
    if (best_of_keypoint[i].second >= 0) (*seen)[best_of_keypoint[i].second] = static_cast<int>(i);
}

std::vector<int64_t> LocalMap::Window() const {
  // A keyframe joins when it shares as many points as a verified motion needs inliers.
  const Keyframe& newest = keyframes_.back();
  std::map<int64_t, int> shared;
  for (const int64_t id : newest.points) {
    const auto p = points_.find(id);
    if (p == points_.end()) continue;
    for (const Observation& o : p->second.observations)
      if (o.keyframe != newest.id) ++shared[o.keyframe];
  }
  std::vector<std::pair<int, int64_t>> ranked;
  for (const auto& [keyframe, count] : shared)
    if (count >= options_.verify.min_inliers) ranked.emplace_back(count, keyframe);
  std::sort(ranked.begin(), ranked.end(), std::greater<>());
  std::vector<int64_t> window = {newest.id};
  for (const auto& [count, keyframe] : ranked) {
    if (static_cast<int>(window.size()) >= options_.local_map.window_keyframes) break;
    window.push_back(keyframe);
  }
  return window;
}

void LocalMap::Adjust(const std::vector<int64_t>& window) {
  std::map<int64_t, int> camera_of;  // keyframe id -> index in cameras
  std::vector<BundleCamera> cameras;
  std::vector<int64_t> camera_ids;
  auto add_camera = [&](int64_t id, bool fixed) {
    const auto [it, added] = camera_of.emplace(id, static_cast<int>(cameras.size()));
    if (!added) return it->second;
    cameras.push_back({Find(id)->world_from_cam, fixed});
    camera_ids.push_back(id);
    return it->second;
  };
  for (const int64_t id : window) add_camera(id, false);
  // The points the window sees (by more than one keyframe), and every observation of them; the
  // keyframes outside the window that see them are held fixed.
  std::vector<int64_t> point_ids;
  std::set<int64_t> taken;
  for (const int64_t id : window)
    for (const int64_t p : Find(id)->points) {
      const auto it = points_.find(p);
      if (it != points_.end() && it->second.observations.size() >= 2 && taken.insert(p).second)
        point_ids.push_back(p);
    }
  std::vector<Eigen::Vector3d> points;
  std::vector<BundleObservation> observations;
  std::vector<std::pair<int64_t, size_t>> source;  // (point id, its observation's index)
  for (const int64_t p : point_ids) {
    MapPoint& mp = points_.at(p);
    const int index = static_cast<int>(points.size());
    points.push_back(mp.world);
    for (size_t k = 0; k < mp.observations.size(); ++k) {
      const Observation& o = mp.observations[k];
      const int camera = add_camera(o.keyframe, true);
      if ((cameras[camera].world_from_cam.inverse() * mp.world).z() <= 0) continue;
      observations.push_back({camera, index, o.measured, o.depth_sigma});
      source.emplace_back(p, k);
    }
  }
  const bool any_fixed =
      std::any_of(cameras.begin(), cameras.end(), [](const BundleCamera& c) { return c.fixed; });
  if (!any_fixed) {  // the gauge: the oldest keyframe of the window stays
    const auto oldest = std::min_element(window.begin(), window.end());
    cameras[camera_of.at(*oldest)].fixed = true;
  }
  // Adjusted, the observations beyond the refinement's inlier bound left out (and out of the
  // map), adjusted again: a wrong association pulls under Huber's loss until it is removed.
  std::map<int64_t, std::vector<size_t>> outliers;
  for (int round = 0; round < 2; ++round) {
    const BundleResult result = BundleAdjust(bundle_, &cameras, &points, observations);
    if (!result.success) return;
    std::vector<BundleObservation> kept;
    std::vector<std::pair<int64_t, size_t>> kept_source;
    for (size_t k = 0; k < observations.size(); ++k) {
      const BundleObservation& o = observations[k];
      const Eigen::Vector3d r = BundleResidual(bundle_, cameras[o.camera].world_from_cam.inverse(),
                                               points[o.point], o.measured, o.depth_sigma);
      if (r.norm() > options_.refine.inlier_sigmas) {
        outliers[source[k].first].push_back(source[k].second);
      } else {
        kept.push_back(o);
        kept_source.push_back(source[k]);
      }
    }
    if (kept.size() == observations.size()) break;
    observations = std::move(kept);
    source = std::move(kept_source);
  }
  for (size_t c = 0; c < cameras.size(); ++c)
    if (!cameras[c].fixed) Find(camera_ids[c])->world_from_cam = cameras[c].world_from_cam;
  for (size_t i = 0; i < point_ids.size(); ++i) points_.at(point_ids[i]).world = points[i];
  for (auto& [p, indices] : outliers) {
    std::sort(indices.begin(), indices.end());
    std::vector<Observation>& obs = points_.at(p).observations;
    for (auto k = indices.rbegin(); k != indices.rend(); ++k)
      obs.erase(obs.begin() + static_cast<std::ptrdiff_t>(*k));
    if (obs.empty()) points_.erase(p);
  }
}

void LocalMap::Cull() {
  // A point no later keyframe saw among the next two is unlikely to be seen again.
  const int64_t newest = keyframes_.back().id;
  for (auto it = points_.begin(); it != points_.end();) {
    if (it->second.observations.size() <= 1 && newest - it->second.first_keyframe >= 2)
      it = points_.erase(it);
    else
      ++it;
  }
  while (static_cast<int>(keyframes_.size()) > options_.local_map.max_keyframes)
    RemoveOldestKeyframe();
}

void LocalMap::RemoveOldestKeyframe() {
  const Keyframe& kf = keyframes_.front();
  const int64_t id = kf.id;
  for (const int64_t p : kf.points) {
    const auto it = points_.find(p);
    if (it == points_.end()) continue;
    std::vector<Observation>& obs = it->second.observations;
    obs.erase(std::remove_if(obs.begin(), obs.end(),
                             [id](const Observation& o) { return o.keyframe == id; }),
              obs.end());
    if (obs.empty()) points_.erase(it);
  }
  keyframes_.pop_front();
}

LocalMap::Keyframe* LocalMap::Find(int64_t id) {
  const auto it = std::lower_bound(keyframes_.begin(), keyframes_.end(), id,
                                   [](const Keyframe& k, int64_t v) { return k.id < v; });
  if (it == keyframes_.end() || it->id != id) throw std::logic_error("LocalMap: no such keyframe");
  return &*it;
}

}  // namespace rgbdvo
