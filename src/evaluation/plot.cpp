#include "rgbdvo/evaluation/plot.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/evaluation/gnuplot.hpp"

namespace rgbdvo {
namespace {

// A 2D panel: horizontal and vertical coordinates of a camera position (x right, y down,
// z forward).
struct Panel {
  const char* title;
  const char* xlabel;
  const char* ylabel;
  const char* columns;  // gnuplot `using` of the data files (columns x y z)
  Eigen::Vector2d (*project)(const Eigen::Vector3d&);
};
const Panel kPanels[] = {
    {"Top view", "x (right) [m]", "z (forward) [m]", "1:3",
     [](const Eigen::Vector3d& p) { return Eigen::Vector2d(p.x(), p.z()); }},
    {"Side view", "z (forward) [m]", "-y (up) [m]", "3:(-$2)",
     [](const Eigen::Vector3d& p) { return Eigen::Vector2d(p.z(), -p.y()); }},
};

// Rows `x y z` of a gnuplot data file.
std::string Points(const std::vector<Eigen::Vector3d>& points) {
  std::ostringstream out;
  out << std::setprecision(9);
  for (const Eigen::Vector3d& p : points) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  return out.str();
}

}  // namespace

void PlotOptions::Check() const {
  if (width_px < 200 || width_px > 10000)
    throw std::invalid_argument("PlotOptions.width_px must be in [200, 10000]");
  if (height_px < 150 || height_px > 10000)
    throw std::invalid_argument("PlotOptions.height_px must be in [150, 10000]");
  if (!(max_dt_s > 0)) throw std::invalid_argument("PlotOptions.max_dt_s must be > 0 s");
  if (gnuplot.empty()) throw std::invalid_argument("PlotOptions.gnuplot must not be empty");
}

std::string PlotResult::Brief() const {
  std::ostringstream s;
  s << "wrote " << png_path << ": estimate " << estimate_poses << " poses";
  if (groundtruth_poses == 0) return s.str() + ", no ground truth";
  if (!aligned) return s.str() + ", ground truth not drawn (" + ate.reason + ")";
  s << ", " << ate.matched << " poses matched with ground truth, rigidly aligned (ATE rmse "
    << std::fixed << std::setprecision(4) << ate.error_m.rmse << " m)";
  return s.str();
}

PlotResult PlotTrajectory(const std::vector<StampedPose>& estimate_poses,
                          const std::vector<StampedPose>& groundtruth, const std::string& png_path,
                          const PlotOptions& options) {
  options.Check();
  if (estimate_poses.empty()) throw std::runtime_error("plot: the estimate has no poses");
  // Counted and matched as the same poses written to a file and read back (`rgbdvo eval`).
  std::vector<StampedPose> estimate = estimate_poses;
  KeepLastOfEachTime(&estimate);
  PlotResult result;
  result.png_path = png_path;
  result.estimate_poses = static_cast<int>(estimate.size());
  result.groundtruth_poses = static_cast<int>(groundtruth.size());

  std::vector<Eigen::Vector3d> est, gt;
  for (const StampedPose& p : estimate) est.push_back(p.world_from_cam.translation());
  if (!groundtruth.empty()) {
    EvaluationOptions eval;
    eval.max_dt_s = options.max_dt_s;
    result.ate = ComputeAte(groundtruth, estimate, eval);
    result.aligned = result.ate.success;
    if (result.aligned) {
      const Rigid3d est_from_gt = result.ate.gt_from_est.inverse();
      for (const StampedPose& p : groundtruth)
        gt.push_back(est_from_gt * p.world_from_cam.translation());
    }
  }

  std::string subtitle = "estimate: " + std::to_string(est.size()) + " poses";
  if (result.aligned) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3) << "   " << result.ate.matched
      << " poses matched with ground truth, rigidly aligned, ATE RMSE " << result.ate.error_m.rmse
      << " m";
    subtitle += s.str();
  } else if (!groundtruth.empty()) {
    subtitle += "   ground truth not drawn: " + result.ate.reason;
  }
  subtitle += "   (frame: first camera)";

  // Layout in screen coordinates: title, subtitle and one legend strip on top, two panels below.
  // Both axes of a panel get the same span in metres and the same length in pixels, so the
  // scale is equal on both axes.
  const std::string title = options.title.empty() ? std::string("trajectory") : options.title;
  const double aspect = double(options.height_px) / options.width_px;
  const double panel_w = std::min(0.41, 0.68 * aspect), panel_h = panel_w / aspect;
  const double bottom = 0.10, top = bottom + panel_h;
  std::ostringstream gp;
  gp << std::setprecision(9) << "set terminal pngcairo noenhanced size " << options.width_px << ","
     << options.height_px << " font 'DejaVu Sans,13' linewidth 1.6\n"
     << "set output 'plot.png'\n"
     << "set multiplot\n"
     << "set label 1001 " << GnuplotQuoted(title)
     << " at screen 0.5, screen 0.965 center font ',16'\n"
     << "set label 1002 " << GnuplotQuoted(subtitle)
     << " at screen 0.5, screen 0.925 center font ',11' tc rgb '#444444'\n"
     << "set border lw 1\nset tics out nomirror\nset mxtics 2\nset mytics 2\nunset key\n"
     << "set grid xtics ytics mxtics mytics lt 1 lw 0.8 lc rgb '#dcdcdc', lt 1 lw 0.6 lc rgb "
        "'#f0f0f0'\n"
     << "set tmargin at screen " << top << "\nset bmargin at screen " << bottom << "\n";
  // Line and point styles, shared by the panels and the legend.
  const std::string gt_style = "with lines lw 2.2 dt (6,3) lc rgb '#555555'";
  const std::string est_style = "with lines lw 2 lc rgb '#1f6fb4'";
  const std::string start_style = "with points pt 7 ps 1.8 lc rgb '#2ca02c'";
  const std::string end_style = "with points pt 5 ps 1.6 lc rgb '#d62728'";
  for (int k = 0; k < 2; ++k) {
    const Panel& panel = kPanels[k];
    Eigen::Vector2d lo = panel.project(est.front()), hi = lo;
    for (const auto* set : {&est, &gt})
      for (const Eigen::Vector3d& p : *set) {
        lo = lo.cwiseMin(panel.project(p));
        hi = hi.cwiseMax(panel.project(p));
      }
    const double span = std::max(0.05, (hi - lo).maxCoeff()) * 1.25;
    const Eigen::Vector2d mid = 0.5 * (lo + hi);
    const double centre = 0.27 + 0.5 * k;  // a little right of the half: room for the y label
    gp << "set lmargin at screen " << centre - panel_w / 2 << "\nset rmargin at screen "
       << centre + panel_w / 2 << "\n"
       << "set title " << GnuplotQuoted(panel.title) << " font ',14'\n"
       << "set xlabel " << GnuplotQuoted(panel.xlabel) << "\nset ylabel "
       << GnuplotQuoted(panel.ylabel) << "\n"
       << "set xrange [" << mid.x() - span / 2 << ":" << mid.x() + span / 2 << "]\n"
       << "set yrange [" << mid.y() - span / 2 << ":" << mid.y() + span / 2 << "]\n";
    const std::string u = std::string(" using ") + panel.columns + " ";
    gp << "plot ";
    if (!gt.empty()) gp << "'gt.dat'" << u << gt_style << ", ";
    gp << "'est.dat'" << u << est_style << ", 'start.dat'" << u << start_style << ", 'end.dat'" << u
       << end_style << "\n"
       << "unset label 1001\nunset label 1002\n";
  }
  // The legend: an empty full-width plot whose key is the only thing drawn.
  gp << "unset title\nunset xlabel\nunset ylabel\nunset border\nunset tics\nunset grid\n"
     << "set lmargin at screen 0.05\nset rmargin at screen 0.95\n"
     << "set tmargin at screen 0.90\nset bmargin at screen 0.85\n"
     << "set xrange [0:1]\nset yrange [0:1]\n"
     << "set key center center horizontal box lc rgb '#bbbbbb' samplen 3 width 2 font ',12'\n"
     << "plot ";
  if (!gt.empty()) gp << "NaN " << gt_style << " title 'ground truth (aligned)', ";
  gp << "NaN " << est_style << " title 'estimate', NaN " << start_style << " title 'start', NaN "
     << end_style << " title 'end'\n"
     << "unset multiplot\n";
  // gnuplot writes into a temporary folder; the image is then copied to where the user asked,
  // so the user's path never enters the script.
  RenderGnuplot(options.gnuplot, gp.str(),
                {{"est.dat", Points(est)},
                 {"gt.dat", Points(gt)},
                 {"start.dat", Points({est.front()})},
                 {"end.dat", Points({est.back()})}},
                png_path);
  return result;
}

}  // namespace rgbdvo
