#include "rgbdvo/calibrate/auto_calibrate.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/sensor/camera.hpp"

namespace rgbdvo {
namespace {

// A depth-edge point: between an IR pixel on the near side of a depth jump and its farther
// neighbour (the midpoint, where the outline lies), with the near depth.
struct EdgePoint {
  float u_ir = 0, v_ir = 0, z_m = 0;
  int frame = 0;  // index into the used frames' distance images
};

bool InRange(float z, const Calibration& c) { return z >= c.min_depth_m && z <= c.max_depth_m; }

// The depth-edge points of one frame (frame = `frame_id`): each pair of 4-neighbours, both with
// a depth in range, whose depths differ by more than jump_ratio times the nearer one.
std::vector<EdgePoint> DepthEdges(const cv::Mat& depth, const Calibration& calib, double jump_ratio,
                                  int frame_id, int* readings) {
  std::vector<EdgePoint> edges;
  *readings = 0;
  const auto add = [&](int u, int v, int du, int dv, float z, float zn) {
    if (!InRange(zn, calib)) return;
    const float near = std::min(z, zn);
    if (std::abs(z - zn) <= jump_ratio * near) return;
    edges.push_back(
        {static_cast<float>(u + 0.5 * du), static_cast<float>(v + 0.5 * dv), near, frame_id});
  };
  for (int v = 0; v < depth.rows; ++v) {
    const float* row = depth.ptr<float>(v);
    const float* below = v + 1 < depth.rows ? depth.ptr<float>(v + 1) : nullptr;
    for (int u = 0; u < depth.cols; ++u) {
      if (!InRange(row[u], calib)) continue;
      ++*readings;
      if (u + 1 < depth.cols) add(u, v, 1, 0, row[u], row[u + 1]);
      if (below) add(u, v, 0, 1, row[u], below[u]);
    }
  }
  return edges;
}

// Canny edges of any colour channel: an outline between two surfaces of equal grey is still an
// edge in colour.
cv::Mat ColorEdges(const AutoCalibrateOptions& o, const cv::Mat& blurred_bgr) {
  cv::Mat channels[3], edges, any;
  cv::split(blurred_bgr, channels);
  for (const cv::Mat& c : channels) {
    cv::Canny(c, edges, o.canny_low, o.canny_high);
    any = any.empty() ? edges : (any | edges);
  }
  return any;
}

cv::Mat Blurred(const cv::Mat& bgr) {
  cv::Mat blurred;
  cv::GaussianBlur(bgr, blurred, cv::Size(0, 0), 1.0);
  return blurred;
}

// Distance (px, CV_32FC1) to the nearest colour edge, truncated at max_px. Canny keeps the
// lower-index pixel of the two equal gradient maxima a sharp step makes, half a pixel off the
// step; so the distances of the image's and of the flipped image's edges are averaged, which
// centres them on the step.
cv::Mat ColorDistance(const AutoCalibrateOptions& o, const cv::Mat& bgr, double max_px) {
  const cv::Mat blurred = Blurred(bgr);
  cv::Mat flipped, flipped_edges, dist, dist_flipped;
  cv::flip(blurred, flipped, -1);
  cv::flip(ColorEdges(o, flipped), flipped_edges, -1);
  cv::distanceTransform(ColorEdges(o, blurred) == 0, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::distanceTransform(flipped_edges == 0, dist_flipped, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  dist = 0.5 * (dist + dist_flipped);
  return cv::min(dist, max_px);
}

// Bilinear sample of a CV_32FC1 image; false when (x, y) is within 1 px of the border or outside.
bool Bilinear(const cv::Mat& img, double x, double y, double* value) {
  if (!(x >= 1 && y >= 1 && x < img.cols - 2 && y < img.rows - 2)) return false;
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double fx = x - x0, fy = y - y0;
  const float* r0 = img.ptr<float>(y0) + x0;
  const float* r1 = img.ptr<float>(y0 + 1) + x0;
  *value = (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
  return true;
}

// The fit's data: depth-edge points and, per used frame, the colour edges' distance image.
struct Problem {
  std::vector<EdgePoint> points;
  std::vector<cv::Mat> distance;
  double typical_z = 2.0;  // median edge depth, m: where mappings are compared
  cv::Size ir_size;
  Eigen::Vector2d disparity = Eigen::Vector2d::Zero();  // the start's s_u, s_v, px m (kept)
};

// Distance of point p, mapped by `params`, to its nearest colour edge; false when it maps
// outside the colour image. With `grad`, also d(distance) / d(params).
bool PointDistance(const Problem& pr, const EdgePoint& p, const AutoCalibParams& params, double* d,
                   AutoCalibParams* grad = nullptr) {
  Eigen::Matrix<double, 2, kAutoCalibParams> J;
  const Eigen::Vector2d uv =
      IrToColorPixel(params, pr.disparity, p.u_ir, p.v_ir, p.z_m, grad ? &J : nullptr);
  const cv::Mat& dist = pr.distance[p.frame];
  if (!Bilinear(dist, uv.x(), uv.y(), d)) return false;
  if (grad) {
    double xp = 0, xm = 0, yp = 0, ym = 0;  // inside: the margin of Bilinear is 1 px
    Bilinear(dist, uv.x() + 0.5, uv.y(), &xp);
    Bilinear(dist, uv.x() - 0.5, uv.y(), &xm);
    Bilinear(dist, uv.x(), uv.y() + 0.5, &yp);
    Bilinear(dist, uv.x(), uv.y() - 0.5, &ym);
    *grad = J.transpose() * Eigen::Vector2d(xp - xm, yp - ym);
  }
  return true;
}

// Truncated quadratic over the points [begin, end) with step `stride`: sum of min(d, tau)^2.
double Cost(const Problem& pr, const std::vector<int>& idx, const AutoCalibParams& params,
            double tau) {
  double sum = 0, d = 0;
  for (int i : idx) {
    if (PointDistance(pr, pr.points[i], params, &d) && d < tau)
      sum += d * d;
    else
      sum += tau * tau;
  }
  return sum;
}

// Largest difference, px, between where two parameter sets map the IR image's corners and centre
// (at the typical edge depth).
double MappingDifference(const Problem& pr, const AutoCalibParams& a, const AutoCalibParams& b) {
  double worst = 0;
  const double w = pr.ir_size.width - 1, h = pr.ir_size.height - 1;
  for (const Eigen::Vector2d& c :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0), Eigen::Vector2d(0, h), Eigen::Vector2d(w, h),
        Eigen::Vector2d(w / 2, h / 2)})
    worst = std::max(worst, (IrToColorPixel(a, pr.disparity, c.x(), c.y(), pr.typical_z) -
                             IrToColorPixel(b, pr.disparity, c.x(), c.y(), pr.typical_z))
                                .norm());
  return worst;
}

// How evenly the edge points pin the mapping down: the smallest over the largest lambda of
// H x = lambda G x, where H is the Gauss-Newton matrix of the points within
// tau (sum of g g^T, g = d(distance)/d(params)) and G = M^T M, M the derivative of where the IR
// image's corners map (at the typical depth). For a mapping change moving the corners by 1 px
// (RMS), the summed squared distance change is 4 lambda: about the number of edge points that
// see that change. Outlines in one direction only leave a change that few points see.
double ConstraintRatio(const Problem& pr, const std::vector<int>& idx, const AutoCalibParams& p,
                       double tau) {
  Eigen::Matrix<double, kAutoCalibParams, kAutoCalibParams> H, G;
  H.setZero();
  G.setZero();
  AutoCalibParams g;
  double d = 0;
  for (int i : idx)
    if (PointDistance(pr, pr.points[i], p, &d, &g) && d < tau) H += g * g.transpose();
  const double w = pr.ir_size.width - 1, h = pr.ir_size.height - 1;
  Eigen::Matrix<double, 2, kAutoCalibParams> J;
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0),
                                   Eigen::Vector2d(0, h), Eigen::Vector2d(w, h)}) {
    IrToColorPixel(p, pr.disparity, c.x(), c.y(), pr.typical_z, &J);
    G += J.transpose() * J;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<decltype(H)> solver(H, G, Eigen::EigenvaluesOnly);
  return solver.eigenvalues().minCoeff() / std::max(solver.eigenvalues().maxCoeff(), 1e-12);
}

struct Refined {
  AutoCalibParams params;
  double cost = 0;  // at the last truncation
  int iterations = 0;
  bool converged = false;
};

// Levenberg-Marquardt on the truncated quadratic at truncation tau, from `start`. Points
// beyond tau count as outliers (constant cost, no gradient): iteratively reweighted least
// squares with 0/1 weights.
Refined Refine(const Problem& pr, const std::vector<int>& idx, const AutoCalibParams& start,
               double tau, int max_iterations) {
  Refined r{start, Cost(pr, idx, start, tau), 0, false};
  double lambda = 1e-3;
  while (r.iterations < max_iterations) {
    ++r.iterations;
    Eigen::Matrix<double, kAutoCalibParams, kAutoCalibParams> H;
    AutoCalibParams b, g;
    H.setZero();
    b.setZero();
    double d = 0;
    for (int i : idx) {
      if (!PointDistance(pr, pr.points[i], r.params, &d, &g) || d >= tau) continue;
      H += g * g.transpose();
      b += g * d;
    }
    bool accepted = false;
    while (lambda < 1e10) {
      Eigen::Matrix<double, kAutoCalibParams, kAutoCalibParams> damped = H;
      damped.diagonal() *= 1 + lambda;
      damped.diagonal().array() += 1e-12;
      const AutoCalibParams next = r.params - damped.ldlt().solve(b);
      const double cost = Cost(pr, idx, next, tau);
      if (std::isfinite(cost) && cost < r.cost) {
        const double moved = MappingDifference(pr, next, r.params);
        const double gain = r.cost - cost;
        r.params = next;
        r.cost = cost;
        lambda = std::max(lambda / 4, 1e-9);
        accepted = true;
        if (moved < 1e-3 || gain < 1e-9 * cost) r.converged = true;
        break;
      }
      lambda *= 8;
    }
    if (!accepted) r.converged = true;  // no step lowers the cost: a minimum
    if (r.converged) break;
  }
  return r;
}

// Coarse-to-fine refinement: truncation halved from coarse to fine.
Refined RefineLevels(const AutoCalibrateOptions& o, const Problem& pr, const std::vector<int>& idx,
                     const AutoCalibParams& start) {
  Refined r{start, 0, 0, true};
  int iterations = 0;
  for (double tau = o.coarse_truncation_px;; tau = std::max(tau / 2, o.fine_truncation_px)) {
    r = Refine(pr, idx, r.params, tau, o.max_iterations);
    iterations += r.iterations;
    if (tau <= o.fine_truncation_px) break;
  }
  r.iterations = iterations;
  return r;
}

// Grid over A, C (around the start, keeping the image centre's IR pixel) and the centre's IR
// pixel offsets; the `keep` best mutually distinct candidates, best first.
std::vector<AutoCalibParams> GridSearch(const AutoCalibrateOptions& o, const Problem& pr,
                                        const std::vector<int>& idx, const AutoCalibParams& start,
                                        const cv::Size& color_size, int keep) {
  const double step_px = o.coarse_truncation_px / 2;
  const int n_off = static_cast<int>(std::ceil(o.search_offset_px / step_px));
  const double cu = (color_size.width - 1) / 2.0, cv_ = (color_size.height - 1) / 2.0;
  const auto scales = [&](double s0, double centre) {
    const double ds = step_px / (std::abs(s0) * std::max(centre, 1.0));
    const int n = static_cast<int>(std::ceil(o.search_scale / ds));
    std::vector<double> out;
    for (int k = -n; k <= n; ++k) out.push_back(s0 * (1 + k * ds));
    return out;
  };
  const std::vector<double> As = scales(start[0], cu), Cs = scales(start[2], cv_);
  std::vector<std::pair<double, AutoCalibParams>> scored;
  for (double a : As)
    for (double c : Cs)
      for (int i = -n_off; i <= n_off; ++i)
        for (int j = -n_off; j <= n_off; ++j) {
          AutoCalibParams p = start;
          p[0] = a;
          p[1] = start[1] + (start[0] - a) * cu + i * step_px;
          p[2] = c;
          p[3] = start[3] + (start[2] - c) * cv_ + j * step_px;
          scored.emplace_back(Cost(pr, idx, p, o.coarse_truncation_px), p);
        }
  std::sort(scored.begin(), scored.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<AutoCalibParams> best;
  for (const auto& [cost, p] : scored) {
    bool distinct = true;
    for (const AutoCalibParams& q : best)
      distinct = distinct && MappingDifference(pr, p, q) > o.coarse_truncation_px;
    if (distinct) best.push_back(p);
    if (static_cast<int>(best.size()) == keep) break;
  }
  return best;
}

// Every k-th of n indices so that about `count` remain.
std::vector<int> Spread(int n, int count) {
  std::vector<int> idx;
  if (n <= count) {
    idx.resize(n);
    std::iota(idx.begin(), idx.end(), 0);
    return idx;
  }
  for (int k = 0; k < count; ++k)
    idx.push_back(static_cast<int>(static_cast<int64_t>(k) * n / count));
  return idx;
}

std::string Fixed(double x, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

}  // namespace

void AutoCalibrateOptions::Check() const {
  const auto need = [](bool ok, const char* field, const char* rule) {
    if (!ok)
      throw std::invalid_argument(std::string("AutoCalibrateOptions.") + field + " must be " +
                                  rule);
  };
  need(max_frames >= 1, "max_frames", ">= 1");
  need(min_frames >= 1 && min_frames <= max_frames, "min_frames", "in [1, max_frames]");
  need(min_edge_points_per_frame >= 1, "min_edge_points_per_frame", ">= 1");
  need(depth_jump_ratio > 0, "depth_jump_ratio", "> 0");
  need(canny_low > 0, "canny_low", "> 0");
  need(canny_high >= canny_low, "canny_high", ">= canny_low");
  need(search_scale >= 0 && search_scale < 0.9, "search_scale", "in [0, 0.9)");
  need(search_offset_px >= 0, "search_offset_px", ">= 0");
  need(fine_truncation_px > 0, "fine_truncation_px", "> 0");
  need(coarse_truncation_px >= fine_truncation_px, "coarse_truncation_px", ">= fine_truncation_px");
  need(inlier_px > 0, "inlier_px", "> 0");
  need(min_inlier_fraction >= 0 && min_inlier_fraction <= 1, "min_inlier_fraction", "in [0, 1]");
  need(max_points >= 10, "max_points", ">= 10");
  need(grid_points >= 10, "grid_points", ">= 10");
  need(max_iterations >= 1, "max_iterations", ">= 1");
  need(uncertainty_subsets >= 2, "uncertainty_subsets", ">= 2");
  need(max_corner_sigma_px > 0, "max_corner_sigma_px", "> 0");
  need(warn_corner_sigma_px > 0, "warn_corner_sigma_px", "> 0");
  need(min_constraint_ratio >= 0 && min_constraint_ratio < 1, "min_constraint_ratio", "in [0, 1)");
}

std::string AutoCalibration::Brief() const {
  if (!success) return "auto-calibration failed: " + reason;
  std::ostringstream s;
  s << "A=" << Fixed(A, 5) << "+-" << Fixed(sigma_A, 5) << " B=" << Fixed(B, 2) << "+-"
    << Fixed(sigma_B, 2) << " C=" << Fixed(C, 5) << "+-" << Fixed(sigma_C, 5)
    << " D=" << Fixed(D, 2) << "+-" << Fixed(sigma_D, 2) << " from " << frames_used << " of "
    << frames_given << " frames, " << edge_points << " depth-edge points, "
    << Fixed(100 * inlier_fraction, 0) << " % inliers, RMS " << Fixed(rms_px, 2)
    << " px, constraint ratio " << Fixed(constraint_ratio, 2);
  return s.str();
}

AutoCalibParams ParamsFromCalibration(const Calibration& c) {
  return AutoCalibParams(c.A, c.B, c.C, c.D);
}

void ParamsToCalibration(const AutoCalibParams& p, Calibration* c) {
  c->A = p[0], c->B = p[1], c->C = p[2], c->D = p[3];
}

Eigen::Vector2d IrToColorPixel(const AutoCalibParams& p, const Eigen::Vector2d& disparity,
                               double u_ir, double v_ir, double z_m,
                               Eigen::Matrix<double, 2, kAutoCalibParams>* jacobian) {
  const double u = (u_ir - p[1] - disparity.x() / z_m) / p[0];
  const double v = (v_ir - p[3] - disparity.y() / z_m) / p[2];
  if (jacobian) {
    *jacobian << -u / p[0], -1 / p[0], 0, 0,  //
        0, 0, -v / p[2], -1 / p[2];
  }
  return {u, v};
}

namespace {

// Pools the frames' depth edges (subsampled evenly) and their colour distance images into
// *problem; *used_frames: the index into frames of each distance image. False with
// out->reason when the frames hold too few edges.
bool PoolEdges(const AutoCalibrateOptions& o, const std::vector<Frame>& frames,
               const Calibration& start, Problem* problem, std::vector<int>* used_frames,
               AutoCalibration* out) {
  const std::string range = " (" + Fixed(start.min_depth_m, 2) + "-" + Fixed(start.max_depth_m, 2) +
                            " m, the calibration's range)";

  Problem& pr = *problem;
  std::vector<int>& used = *used_frames;
  AutoCalibration& result = *out;
  pr.ir_size = frames.front().depth_m.size();
  int64_t readings = 0, all_edges = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    int n = 0;
    std::vector<EdgePoint> e =
        DepthEdges(frames[k].depth_m, start, o.depth_jump_ratio, static_cast<int>(used.size()), &n);
    readings += n;
    all_edges += static_cast<int64_t>(e.size());
    if (static_cast<int>(e.size()) < o.min_edge_points_per_frame) continue;
    used.push_back(static_cast<int>(k));
    pr.points.insert(pr.points.end(), e.begin(), e.end());
  }
  result.frames_used = static_cast<int>(used.size());
  if (readings == 0) {
    result.reason = "no depth readings in " + std::to_string(frames.size()) +
                    " frames: all depths are zero or out of range" + range;
    return false;
  }
  if (all_edges == 0) {
    result.reason = "no depth edges (neighbours more than " + Fixed(100 * o.depth_jump_ratio, 0) +
                    " % apart) in " + std::to_string(frames.size()) +
                    " frames: a flat scene? Record objects in front of a background";
    return false;
  }
  if (result.frames_used < o.min_frames) {
    result.reason = "only " + std::to_string(result.frames_used) + " of " +
                    std::to_string(frames.size()) +
                    " frames have >= " + std::to_string(o.min_edge_points_per_frame) +
                    " depth-edge points, need " + std::to_string(o.min_frames);
    return false;
  }
  // Subsample the pooled points evenly (they are in frame order, so every frame keeps its share).
  {
    std::vector<EdgePoint> kept;
    for (int i : Spread(static_cast<int>(pr.points.size()), o.max_points))
      kept.push_back(pr.points[i]);
    pr.points.swap(kept);
  }
  result.edge_points = static_cast<int>(pr.points.size());
  {
    std::vector<float> z;
    z.reserve(pr.points.size());
    for (const EdgePoint& p : pr.points) z.push_back(p.z_m);
    std::nth_element(z.begin(), z.begin() + z.size() / 2, z.end());
    pr.typical_z = z[z.size() / 2];
  }
  pr.disparity = Eigen::Vector2d(start.s_u, start.s_v);
  for (int k : used) pr.distance.push_back(ColorDistance(o, frames[k].bgr, o.coarse_truncation_px));

  return true;
}

// The fit's uncertainty: the spread of fits on disjoint blocks of consecutive used frames
// (sigma_A-D, corner_sigma_px in *out). False with out->reason when they disagree too much.
bool MeasureUncertainty(const AutoCalibrateOptions& o, const Problem& pr, int frames_used,
                        const AutoCalibParams& p, AutoCalibration* out) {
  AutoCalibration& result = *out;
  // Uncertainty: the spread of fits on disjoint blocks of consecutive used frames.
  const int k = std::min(o.uncertainty_subsets, frames_used);
  if (k >= 2) {
    std::vector<AutoCalibParams> fits;
    for (int s = 0; s < k; ++s) {
      const int lo = s * frames_used / k;
      const int hi = (s + 1) * frames_used / k;
      std::vector<int> idx;
      for (size_t i = 0; i < pr.points.size(); ++i)
        if (pr.points[i].frame >= lo && pr.points[i].frame < hi) idx.push_back(static_cast<int>(i));
      fits.push_back(Refine(pr, idx, p, o.fine_truncation_px, o.max_iterations).params);
    }
    AutoCalibParams mean = AutoCalibParams::Zero(), var = AutoCalibParams::Zero();
    for (const AutoCalibParams& f : fits) mean += f / k;
    for (const AutoCalibParams& f : fits) var += (f - mean).cwiseAbs2() / (k - 1);
    const AutoCalibParams sigma = (var / k).cwiseSqrt();
    // The same spread of where the IR image's corners map, px.
    const double w = pr.ir_size.width - 1, h = pr.ir_size.height - 1;
    for (const Eigen::Vector2d& c : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0),
                                     Eigen::Vector2d(0, h), Eigen::Vector2d(w, h)}) {
      const auto at = [&](const AutoCalibParams& q) {
        return IrToColorPixel(q, pr.disparity, c.x(), c.y(), pr.typical_z);
      };
      Eigen::Vector2d m = Eigen::Vector2d::Zero();
      for (const AutoCalibParams& f : fits) m += at(f) / k;
      double v = 0;
      for (const AutoCalibParams& f : fits) v += (at(f) - m).squaredNorm() / (k - 1);
      result.corner_sigma_px = std::max(result.corner_sigma_px, std::sqrt(v / k));
    }
    result.sigma_A = sigma[0], result.sigma_B = sigma[1], result.sigma_C = sigma[2],
    result.sigma_D = sigma[3];
    if (result.corner_sigma_px > o.max_corner_sigma_px) {
      result.reason =
          "the edges do not pin the mapping down: fits on " + std::to_string(k) +
          " parts of the recording disagree by " + Fixed(result.corner_sigma_px, 1) +
          " px (1-sigma) at the image corners, need <= " + Fixed(o.max_corner_sigma_px, 1) +
          " px; record objects whose outlines run in several directions across "
          "the image";
      return false;
    }
  }
  return true;
}

}  // namespace

AutoCalibration AutoCalibrate(const AutoCalibrateOptions& o, const std::vector<Frame>& frames,
                              const Calibration& start) {
  o.Check();
  start.Check();
  if (frames.empty()) throw std::invalid_argument("AutoCalibrate: no frames");
  for (const Frame& f : frames)
    if (f.bgr.type() != CV_8UC3 || f.depth_m.type() != CV_32FC1 || f.bgr.empty() ||
        f.depth_m.empty())
      throw std::invalid_argument("AutoCalibrate: frame " + std::to_string(f.index) + " (" +
                                  f.name + "): need CV_8UC3 colour and CV_32FC1 depth");
  AutoCalibration result;
  result.frames_given = static_cast<int>(frames.size());
  Problem pr;
  std::vector<int> used;  // index into frames per distance image
  if (!PoolEdges(o, frames, start, &pr, &used, &result)) return result;

  std::vector<int> all(pr.points.size());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<int> grid_idx = Spread(static_cast<int>(pr.points.size()), o.grid_points);
  const AutoCalibParams start_params = ParamsFromCalibration(start);
  Refined best;
  bool have = false;
  int iterations = 0;
  for (const AutoCalibParams& candidate :
       GridSearch(o, pr, grid_idx, start_params, frames[used.front()].bgr.size(), 5)) {
    const Refined r = RefineLevels(o, pr, all, candidate);
    iterations += r.iterations;
    if (!have || r.cost < best.cost) best = r, have = true;
  }
  result.iterations = iterations;
  if (!best.converged) {
    result.reason = "the fit did not converge in " + std::to_string(o.max_iterations) +
                    " iterations at the finest truncation";
    return result;
  }
  const AutoCalibParams& p = best.params;
  if (!(p[0] > 0) || !(p[2] > 0)) {
    result.reason = "the fit gave a non-positive A or C";
    return result;
  }

  // Inliers and their residuals.
  std::vector<int> inliers_per_frame(used.size(), 0);
  double sum_sq = 0, d = 0;
  int inliers = 0;
  for (const EdgePoint& e : pr.points) {
    if (!PointDistance(pr, e, p, &d) || d >= o.inlier_px) continue;
    ++inliers, sum_sq += d * d, ++inliers_per_frame[e.frame];
  }
  result.inlier_fraction = static_cast<double>(inliers) / static_cast<double>(pr.points.size());
  result.rms_px = inliers > 0 ? std::sqrt(sum_sq / inliers) : 0;
  result.constraint_ratio = ConstraintRatio(pr, all, p, o.fine_truncation_px);
  result.picture_frame = used[std::max_element(inliers_per_frame.begin(), inliers_per_frame.end()) -
                              inliers_per_frame.begin()];
  Calibration fitted = start;
  ParamsToCalibration(p, &fitted);
  result.A = fitted.A, result.B = fitted.B, result.C = fitted.C, result.D = fitted.D;
  if (result.inlier_fraction < o.min_inlier_fraction) {
    result.reason = "the depth edges do not agree with the colour edges: " +
                    Fixed(100 * result.inlier_fraction, 0) + " % inliers at the best fit, need " +
                    Fixed(100 * o.min_inlier_fraction, 0) + " %";
    return result;
  }

  if (result.constraint_ratio < o.min_constraint_ratio) {
    result.reason = "the edges do not pin the mapping down: its least constrained change is " +
                    Fixed(1 / std::max(result.constraint_ratio, 1e-9), 0) +
                    " times weaker than its best (need <= " + Fixed(1 / o.min_constraint_ratio, 0) +
                    "); record objects whose outlines run in several directions across the image";
    return result;
  }

  if (!MeasureUncertainty(o, pr, static_cast<int>(used.size()), p, &result)) return result;
  if (result.corner_sigma_px > o.warn_corner_sigma_px)
    result.warning = "the fit is uncertain by " + Fixed(result.corner_sigma_px, 1) +
                     " px (1-sigma at the image corners, fits on parts of the recording); check "
                     "the residual picture (--png), or record outlines in more directions";
  result.success = true;
  return result;
}

Calibration ApplyAutoCalibration(const Calibration& base, const AutoCalibration& fit,
                                 const std::string& recording) {
  if (!fit.success)
    throw std::invalid_argument("ApplyAutoCalibration: the fit failed: " + fit.reason);
  Calibration c = base;
  c.A = fit.A, c.B = fit.B, c.C = fit.C, c.D = fit.D;
  std::ostringstream d;
  d << "A-D fitted by rgbdvo calibrate --auto from the depth and colour edges of "
    << fit.frames_used << " frames of " << recording << " (" << fit.edge_points
    << " depth-edge points, " << Fixed(100 * fit.inlier_fraction, 0) << " % inliers, RMS "
    << Fixed(fit.rms_px, 2) << " px; 1-sigma A " << Fixed(fit.sigma_A, 5) << ", B "
    << Fixed(fit.sigma_B, 2) << " px, C " << Fixed(fit.sigma_C, 5) << ", D "
    << Fixed(fit.sigma_D, 2) << " px).";
  if (!base.description.empty()) d << " Other fields: " << base.description;
  c.description = d.str();
  c.Check();
  return c;
}

cv::Mat AutoCalibrationPicture(const AutoCalibrateOptions& o, const Frame& frame,
                               const Calibration& calib) {
  o.Check();
  const cv::Mat& depth = frame.depth_m;
  if (depth.type() != CV_32FC1 || frame.bgr.type() != CV_8UC3)
    throw std::invalid_argument("AutoCalibrationPicture: need CV_8UC3 colour and CV_32FC1 depth");
  double lo = calib.max_depth_m, hi = calib.min_depth_m;
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u)
      if (const float z = depth.at<float>(v, u); InRange(z, calib))
        lo = std::min(lo, static_cast<double>(z)), hi = std::max(hi, static_cast<double>(z));
  cv::Mat grey(depth.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u)
      if (const float z = depth.at<float>(v, u); InRange(z, calib))
        grey.at<uint8_t>(v, u) =
            cv::saturate_cast<uint8_t>(30 + 100 * (hi - z) / std::max(hi - lo, 1e-6));
  cv::Mat picture;
  cv::cvtColor(grey, picture, cv::COLOR_GRAY2BGR);

  cv::Mat depth_edges(depth.size(), CV_8UC1, cv::Scalar(0)), color_edges = depth_edges.clone();
  int readings = 0;
  for (const EdgePoint& e : DepthEdges(depth, calib, o.depth_jump_ratio, 0, &readings))
    depth_edges.at<uint8_t>(static_cast<int>(e.v_ir), static_cast<int>(e.u_ir)) = 255;
  const cv::Mat edges = ColorEdges(o, Blurred(frame.bgr));
  for (int v = 0; v < edges.rows; ++v)
    for (int u = 0; u < edges.cols; ++u) {
      if (!edges.at<uint8_t>(v, u)) continue;
      const std::optional<Eigen::Vector2d> found = FindIrPixel(calib, depth, {u, v});
      if (!found) continue;
      const Eigen::Vector2d& ir = *found;
      const int x = static_cast<int>(std::lround(ir.x())),
                y = static_cast<int>(std::lround(ir.y()));
      if (x >= 0 && y >= 0 && x < depth.cols && y < depth.rows) color_edges.at<uint8_t>(y, x) = 255;
    }
  picture.setTo(cv::Scalar(255, 0, 255), color_edges);
  picture.setTo(cv::Scalar(0, 255, 0), depth_edges);
  cv::Mat near_color;  // within 1 px of a mapped colour edge
  cv::dilate(color_edges, near_color, cv::Mat::ones(3, 3, CV_8UC1));
  picture.setTo(cv::Scalar(255, 255, 255), depth_edges & near_color);
  return picture;
}

std::vector<Frame> ReadSpreadFrames(FrameSource& source, int max_frames) {
  if (max_frames < 1) throw std::invalid_argument("ReadSpreadFrames: max_frames must be >= 1");
  std::vector<Frame> frames;
  if (const std::optional<size_t> size = source.Size()) {
    const int n = static_cast<int>(*size), m = std::min(max_frames, n);
    std::vector<int> wanted;
    wanted.reserve(m);
    for (int k = 0; k < m; ++k)
      wanted.push_back(m == 1 ? 0 : static_cast<int>(std::lround(k * (n - 1.0) / (m - 1))));
    size_t next = 0;
    for (int i = 0; i < n && next < wanted.size(); ++i) {
      if (i != wanted[next]) {
        if (!source.Skip()) break;
        continue;
      }
      std::optional<Frame> f = source.Next();
      if (!f) break;
      frames.push_back(std::move(*f));
      ++next;
    }
    return frames;
  }
  // Unknown length: keep every step-th frame, doubling the step when twice too many are kept.
  int step = 1, i = 0;
  while (std::optional<Frame> f = source.Next()) {
    if (i++ % step != 0) continue;
    frames.push_back(std::move(*f));
    if (static_cast<int>(frames.size()) >= 2 * max_frames) {
      std::vector<Frame> half;
      for (size_t k = 0; k < frames.size(); k += 2) half.push_back(std::move(frames[k]));
      frames.swap(half);
      step *= 2;
    }
  }
  std::vector<Frame> spread;
  for (int k : Spread(static_cast<int>(frames.size()), max_frames))
    spread.push_back(std::move(frames[k]));
  return spread;
}

}  // namespace rgbdvo
