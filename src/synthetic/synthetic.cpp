#include "rgbdvo/synthetic/synthetic.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "rgbdvo/io/opencv_codecs.hpp"
#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/sensor/depth_encoding.hpp"

namespace fs = std::filesystem;

namespace rgbdvo {
namespace {

constexpr int kTextureSize = 1024;
constexpr double kTexelsPerMetre = 220.0;

// A colour and a texel drawn one value per statement: the order in which a call's arguments are
// evaluated is the compiler's choice, and a scene must not depend on it (last value first, the
// order the scenes have always been made in).
cv::Scalar RandomColour(cv::RNG& rng, int low, int high) {
  const int c2 = rng.uniform(low, high);
  const int c1 = rng.uniform(low, high);
  const int c0 = rng.uniform(low, high);
  return {static_cast<double>(c0), static_cast<double>(c1), static_cast<double>(c2)};
}

cv::Point RandomTexel(cv::RNG& rng) {
  const int y = rng.uniform(0, kTextureSize);
  const int x = rng.uniform(0, kTextureSize);
  return {x, y};
}

cv::Mat MakeTexture(cv::RNG& rng) {
  cv::Mat tex(kTextureSize, kTextureSize, CV_8UC3, RandomColour(rng, 60, 200));
  for (int i = 0; i < 900; ++i) {
    const cv::Point c = RandomTexel(rng);
    const cv::Scalar color = RandomColour(rng, 0, 256);
    const int r = rng.uniform(3, 28);
    if (rng.uniform(0, 2) == 0)
      cv::circle(tex, c, r, color, cv::FILLED, cv::LINE_AA);
    else
      cv::rectangle(tex, c, c + cv::Point(r, rng.uniform(3, 28)), color, cv::FILLED, cv::LINE_AA);
  }
  cv::GaussianBlur(tex, tex, cv::Size(0, 0), 1.0);
  return tex;
}

// Feature-poor: a grey with sparse, small, low-contrast marks (a few per square metre).
cv::Mat MakePlainTexture(cv::RNG& rng) {
  const int base = rng.uniform(110, 150);
  cv::Mat tex(kTextureSize, kTextureSize, CV_8UC3, cv::Scalar(base, base + 4, base + 8));
  for (int i = 0; i < 200; ++i) {
    const cv::Point c = RandomTexel(rng);
    const int shade = base + rng.uniform(-30, 31);
    cv::circle(tex, c, rng.uniform(4, 16), cv::Scalar(shade, shade + 4, shade + 8), cv::FILLED,
               cv::LINE_AA);
  }
  cv::GaussianBlur(tex, tex, cv::Size(0, 0), 1.0);
  return tex;
}

cv::Vec3b SampleTexture(const cv::Mat& tex, double s, double t) {
  // Bilinear, wrapping (textures tile the plane).
  const double x = s * kTexelsPerMetre, y = t * kTexelsPerMetre;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  auto wrap = [](double v) {
    int i = static_cast<int>(std::fmod(v, kTextureSize));
    return i < 0 ? i + kTextureSize : i;
  };
  const int x0 = wrap(fx), x1 = wrap(fx + 1), y0 = wrap(fy), y1 = wrap(fy + 1);
  cv::Vec3b out;
  for (int c = 0; c < 3; ++c) {
    const double v = (1 - ax) * (1 - ay) * tex.at<cv::Vec3b>(y0, x0)[c] +
                     ax * (1 - ay) * tex.at<cv::Vec3b>(y0, x1)[c] +
                     (1 - ax) * ay * tex.at<cv::Vec3b>(y1, x0)[c] +
                     ax * ay * tex.at<cv::Vec3b>(y1, x1)[c];
    out[c] = cv::saturate_cast<uchar>(v);
  }
  return out;
}

}  // namespace

SyntheticScene::SyntheticScene(uint32_t seed) {
  cv::RNG rng(seed);
  boxes_.push_back({{-2.0, -1.5, -1.0}, {2.0, 1.5, 4.0}, true, 0});  // the room
  boxes_.push_back({{-1.2, 0.2, 2.2}, {-0.4, 1.5, 3.0}, false, 1});
  boxes_.push_back({{0.5, -0.6, 2.6}, {1.3, 0.3, 3.3}, false, 2});
  boxes_.push_back({{-0.3, 0.9, 1.4}, {0.4, 1.5, 2.0}, false, 3});
  for (int i = 0; i < 4; ++i) textures_.push_back(MakeTexture(rng));
}

SyntheticScene SyntheticScene::RobotHall(uint32_t seed) {
  SyntheticScene s{Empty{}};
  cv::RNG rng(seed);
  // {lo, hi} in metres; the floor is y = 0, heights are negative y.
  s.boxes_.push_back({{-4.5, -2.5, -3.5}, {4.5, 0.0, 3.5}, true, 0});     // the hall
  s.boxes_.push_back({{-1.1, -0.7, -0.5}, {-0.5, 0.0, 0.3}, false, 1});   // inside, left side
  s.boxes_.push_back({{2.3, -1.1, 2.7}, {3.0, 0.0, 3.5}, false, 2});      // by the far wall
  s.boxes_.push_back({{-3.4, -0.5, -1.2}, {-2.6, 0.0, -0.4}, false, 3});  // outside, left
  s.boxes_.push_back({{-1.2, -0.9, -2.0}, {-0.6, 0.0, -1.6}, false, 1});  // inside, near side
  s.boxes_.push_back({{-4.5, -2.0, 1.0}, {-4.0, 0.0, 2.2}, false, 2});    // a cabinet
  // The feature-poor stretch: a mat 2 mm thick and a panel 1 cm in front of the wall.
  s.boxes_.push_back({{0.75, -0.002, -3.5}, {2.75, 0.0, 2.0}, false, 4});
  s.boxes_.push_back({{0.0, -2.5, -3.5}, {3.6, 0.0, -3.49}, false, 4});
  for (int i = 0; i < 4; ++i) s.textures_.push_back(MakeTexture(rng));
  s.textures_.push_back(MakePlainTexture(rng));
  return s;
}

bool SyntheticScene::Cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double* t_hit,
                          cv::Vec3b* color) const {
  double best = std::numeric_limits<double>::infinity();
  int best_box = -1, best_axis = -1;
  for (size_t b = 0; b < boxes_.size(); ++b) {
    const Box& box = boxes_[b];
    double t_near = -std::numeric_limits<double>::infinity();
    double t_far = std::numeric_limits<double>::infinity();
    int axis_near = -1, axis_far = -1;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(d[a]) < 1e-12) {
        if (o[a] < box.lo[a] || o[a] > box.hi[a]) t_near = t_far + 1;  // parallel and outside
        continue;
      }
      double t0 = (box.lo[a] - o[a]) / d[a], t1 = (box.hi[a] - o[a]) / d[a];
      if (t0 > t1) std::swap(t0, t1);
      if (t0 > t_near) t_near = t0, axis_near = a;
      if (t1 < t_far) t_far = t1, axis_far = a;
    }
    if (t_near > t_far) continue;
    const double t = box.inside_view ? t_far : t_near;
    const int axis = box.inside_view ? axis_far : axis_near;
    if (t > 1e-6 && t < best) best = t, best_box = static_cast<int>(b), best_axis = axis;
  }
  if (best_box < 0) return false;
  *t_hit = best;
  if (color) {
    const Eigen::Vector3d p = o + best * d;
    // Texture coordinates: the two coordinates in the face plane, offset per axis.
    const int u_axis = best_axis == 0 ? 2 : 0, v_axis = best_axis == 1 ? 2 : 1;
    *color = SampleTexture(textures_[boxes_[best_box].texture], p[u_axis] + 3.1 * best_axis,
                           p[v_axis] + 1.7 * best_axis);
  }
  return true;
}

cv::Mat SyntheticScene::RenderColor(const PinholeCamera& cam, const Rigid3d& world_from_cam) const {
  cv::Mat img(cam.height, cam.width, CV_8UC3, cv::Scalar::all(0));
  const Eigen::Vector3d o = world_from_cam.translation();
  const Eigen::Matrix3d R = world_from_cam.linear();
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const Eigen::Vector3d d =
          R * Eigen::Vector3d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1);
      double t;
      cv::Vec3b c;
      if (Cast(o, d, &t, &c)) img.at<cv::Vec3b>(v, u) = c;
    }
  return img;
}

cv::Mat SyntheticScene::RenderDepth(const PinholeCamera& cam, const Rigid3d& world_from_cam) const {
  cv::Mat depth(cam.height, cam.width, CV_32FC1, cv::Scalar(0));
  const Eigen::Vector3d o = world_from_cam.translation();
  const Eigen::Matrix3d R = world_from_cam.linear();
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      // The ray has camera-frame Z = 1, so the hit parameter is the Z-depth.
      const Eigen::Vector3d d =
          R * Eigen::Vector3d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1);
      double t;
      if (Cast(o, d, &t, nullptr)) depth.at<float>(v, u) = static_cast<float>(t);
    }
  return depth;
}

std::vector<Rigid3d> MakeSmoothPath(int n, double step_m, double step_deg) {
  std::vector<Rigid3d> path;
  const double a = step_deg * M_PI / 180.0;
  for (int k = 0; k < n; ++k) {
    const double yaw = a * 10 * std::sin(k / 10.0), pitch = a * 5 * std::sin(k / 7.0),
                 roll = a * 3 * std::sin(k / 13.0);
    Rigid3d T = Rigid3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
                     .toRotationMatrix();
    T.translation() =
        step_m * Eigen::Vector3d(10 * std::sin(k / 10.0), 4 * std::sin(k / 8.0), 0.8 * k);
    path.push_back(T);
  }
  return path;
}

std::vector<double> WriteTumSequence(const std::string& folder, const SyntheticScene& scene,
                                     const PinholeCamera& camera,
                                     const std::vector<Rigid3d>& world_from_cam) {
  std::error_code ec;
  fs::create_directories(fs::path(folder) / "rgb", ec);
  fs::create_directories(fs::path(folder) / "depth", ec);
  if (ec) throw std::runtime_error(folder + ": cannot create folder (" + ec.message() + ")");
  std::ofstream rgb_list(fs::path(folder) / "rgb.txt"), depth_list(fs::path(folder) / "depth.txt"),
      gt(fs::path(folder) / "groundtruth.txt");
  if (!rgb_list || !depth_list || !gt) throw std::runtime_error(folder + ": cannot write lists");
  rgb_list << "# color images\n# timestamp filename\n" << std::fixed << std::setprecision(6);
  depth_list << "# depth maps\n# timestamp filename\n" << std::fixed << std::setprecision(6);
  gt << "# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n";
  std::vector<double> stamps;
  for (size_t k = 0; k < world_from_cam.size(); ++k) {
    const double t = 1000.0 + static_cast<double>(k) / 30.0;
    char name[32];
    std::snprintf(name, sizeof(name), "%06zu.png", k);
    const std::string rgb = std::string("rgb/") + name, depth = std::string("depth/") + name;
    if (!ImwriteWithOpenCv((fs::path(folder) / rgb).string(),
                           scene.RenderColor(camera, world_from_cam[k])) ||
        !ImwriteWithOpenCv((fs::path(folder) / depth).string(),
                           Scaled16FromDepth(scene.RenderDepth(camera, world_from_cam[k]), 5000.0)))
      throw std::runtime_error(folder + ": cannot write frame " + name);
    rgb_list << t << ' ' << rgb << '\n';
    depth_list << t + 0.004 << ' ' << depth << '\n';
    WriteTumLine(gt, t, world_from_cam[k]);
    stamps.push_back(t);
  }
  return stamps;
}

}  // namespace rgbdvo
