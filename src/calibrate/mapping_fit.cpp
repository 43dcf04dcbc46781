#include "rgbdvo/calibrate/mapping_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rgbdvo {
namespace {

struct Line {
  double scale = 1, offset = 0, disparity = 0;
};

// Least squares y = scale * x + offset over the pairs with use[i]; centred sums for accuracy.
Line FitLine(const std::vector<double>& x, const std::vector<double>& y,
             const std::vector<bool>& use) {
  double n = 0, mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i)
    if (use[i]) n += 1, mx += x[i], my += y[i];
  mx /= n;
  my /= n;
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i)
    if (use[i]) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  Line l;
  l.scale = sxy / sxx;
  l.offset = my - l.scale * mx;
  return l;
}

// Least squares y = scale * x + offset + disparity * w over the pairs with use[i] (w = 1/z),
// on centred values: the 2x2 normal equations of scale and disparity, then the offset.
Line FitLineWithDisparity(const std::vector<double>& x, const std::vector<double>& w,
                          const std::vector<double>& y, const std::vector<bool>& use) {
  double n = 0, mx = 0, mw = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i)
    if (use[i]) n += 1, mx += x[i], mw += w[i], my += y[i];
  mx /= n, mw /= n, my /= n;
  Eigen::Matrix2d N = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < x.size(); ++i) {
    if (!use[i]) continue;
    const Eigen::Vector2d a(x[i] - mx, w[i] - mw);
    N += a * a.transpose();
    b += a * (y[i] - my);
  }
  const Eigen::Vector2d sol = N.ldlt().solve(b);
  Line l;
  l.scale = sol(0);
  l.disparity = sol(1);
  l.offset = my - l.scale * mx - l.disparity * mw;
  return l;
}

double Spread(const std::vector<double>& x, const std::vector<bool>& use) {
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < x.size(); ++i)
    if (use[i]) lo = std::min(lo, x[i]), hi = std::max(hi, x[i]);
  return hi - lo;
}

}  // namespace

void MappingFitOptions::Check() const {
  if (min_pairs < 3)
    throw std::invalid_argument("MappingFitOptions.min_pairs must be >= 3 (got " +
                                std::to_string(min_pairs) + ")");
  if (!(min_spread_px > 0))
    throw std::invalid_argument("MappingFitOptions.min_spread_px must be > 0");
  if (!(outlier_px > 0)) throw std::invalid_argument("MappingFitOptions.outlier_px must be > 0");
  if (!(min_inverse_depth_spread > 0))
    throw std::invalid_argument("MappingFitOptions.min_inverse_depth_spread must be > 0");
}

std::string MappingFit::Brief() const {
  std::ostringstream s;
  if (!success) return "fit failed: " + reason;
  s << "A=" << A << " B=" << B << " C=" << C << " D=" << D;
  if (depth_aware) s << " s_u=" << s_u << " s_v=" << s_v << " px m";
  s << " from " << num_inliers << " of " << num_pairs << " pairs";
  if (num_inliers < num_pairs) s << " (" << num_pairs - num_inliers << " outlier(s) set aside)";
  s << ", RMS " << rms_px << " px";
  return s.str();
}

MappingFit FitMapping(const MappingFitOptions& options, const std::vector<PixelPair>& pairs) {
  options.Check();
  MappingFit fit;
  fit.num_pairs = static_cast<int>(pairs.size());
  if (fit.num_pairs < options.min_pairs) {
    fit.reason = "need at least " + std::to_string(options.min_pairs) + " pairs, have " +
                 std::to_string(fit.num_pairs);
    return fit;
  }
  std::vector<double> uv, ui, vv, vi, w;
  bool all_depths = true;
  for (const PixelPair& p : pairs) {
    for (double x : {p.u_vis, p.v_vis, p.u_ir, p.v_ir, p.z_ir_m})
      if (!std::isfinite(x)) throw std::invalid_argument("pixel pair with a non-finite coordinate");
    uv.push_back(p.u_vis), ui.push_back(p.u_ir), vv.push_back(p.v_vis), vi.push_back(p.v_ir);
    all_depths = all_depths && p.z_ir_m > 0;
    w.push_back(p.z_ir_m > 0 ? 1.0 / p.z_ir_m : 0.0);
  }
  std::vector<bool> use(pairs.size(), true);
  fit.depth_aware =
      options.fit_disparity && all_depths && Spread(w, use) >= options.min_inverse_depth_spread;
  const auto spread_ok = [&](const std::vector<double>& x, const char* name) {
    const double s = Spread(x, use);
    if (s >= options.min_spread_px) return true;
    std::ostringstream m;
    m << "degenerate pairs: " << name << " spans " << s << " px (need >= " << options.min_spread_px
      << " px; click points spread across the image)";
    fit.reason = m.str();
    return false;
  };
  if (!spread_ok(uv, "u_vis") || !spread_ok(vv, "v_vis")) return fit;

  std::vector<double> residual(pairs.size());
  for (;;) {
    const Line u = fit.depth_aware ? FitLineWithDisparity(uv, w, ui, use) : FitLine(uv, ui, use);
    const Line v = fit.depth_aware ? FitLineWithDisparity(vv, w, vi, use) : FitLine(vv, vi, use);
    fit.A = u.scale, fit.B = u.offset, fit.C = v.scale, fit.D = v.offset;
    fit.s_u = u.disparity, fit.s_v = v.disparity;
    int worst = -1;
    for (size_t i = 0; i < pairs.size(); ++i) {
      residual[i] = std::hypot(fit.A * uv[i] + fit.B + fit.s_u * w[i] - ui[i],
                               fit.C * vv[i] + fit.D + fit.s_v * w[i] - vi[i]);
      if (use[i] && (worst < 0 || residual[i] > residual[worst])) worst = static_cast<int>(i);
    }
    const int inliers = static_cast<int>(std::count(use.begin(), use.end(), true));
    if (!options.robust || residual[worst] <= options.outlier_px || inliers <= options.min_pairs)
      break;
    // Set the worst pair aside unless that leaves the remaining ones degenerate.
    use[worst] = false;
    const int left = inliers - 1;
    if (Spread(uv, use) < options.min_spread_px || Spread(vv, use) < options.min_spread_px ||
        (fit.depth_aware &&
         (Spread(w, use) < options.min_inverse_depth_spread || left <= options.min_pairs))) {
      use[worst] = true;
      break;
    }
  }
  if (fit.A == 0 || fit.C == 0 || !std::isfinite(fit.A) || !std::isfinite(fit.C)) {
    fit.reason = "fitted A or C is zero: the clicked IR points do not move with the colour points";
    return fit;
  }
  double sum_sq = 0;
  fit.num_inliers = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (use[i]) sum_sq += residual[i] * residual[i], ++fit.num_inliers;
  }
  fit.rms_px = std::sqrt(sum_sq / fit.num_inliers);
  fit.residual_px = residual;
  for (bool u : use) fit.outlier.push_back(!u);
  fit.success = true;
  return fit;
}

}  // namespace rgbdvo
