#include "rgbdvo/evaluation/evaluation_plots.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/evaluation/gnuplot.hpp"

namespace rgbdvo {
namespace {

const char* const kColours[] = {"#1f6fb4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};
const std::string kGtStyle = "with lines lw 2.2 dt (6,3) lc rgb '#555555'";

std::string EstimateStyle(size_t k) {
  return std::string("with lines lw 1.8 lc rgb '") + kColours[k % 6] + "'";
}

// Rows `t x y z roll pitch yaw` (s, m, degrees) of a gnuplot data file; R = Rz Ry Rx.
std::string PoseRows(const std::vector<StampedPose>& poses, double t0) {
  std::ostringstream out;
  out << std::setprecision(9);
  for (const StampedPose& p : poses) {
    const Eigen::Matrix3d& R = p.world_from_cam.linear();
    const Eigen::Vector3d& t = p.world_from_cam.translation();
    const double deg = 180 / M_PI;
    out << p.timestamp - t0 << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' '
        << std::atan2(R(2, 1), R(2, 2)) * deg << ' '
        << std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0))) * deg << ' '
        << std::atan2(R(1, 0), R(0, 0)) * deg << '\n';
  }
  return out.str();
}

// An estimate's poses as ComputeAte saw them (shifted, one per time), in the ground truth's
// frame by its alignment.
std::vector<StampedPose> AlignedPoses(const PlottedEstimate& e, double t_offset_s) {
  std::vector<StampedPose> out = e.poses;
  for (StampedPose& p : out) p.timestamp += t_offset_s;
  KeepLastOfEachTime(&out);
  for (StampedPose& p : out) p.world_from_cam = e.ate.Aligned(p.world_from_cam);
  return out;
}

// Title, subtitle and the multiplot header of a figure.
std::string Header(const EvaluationPlotOptions& o, int width, int height,
                   const std::string& subtitle) {
  const std::string title = o.title.empty() ? std::string("evaluation") : o.title;
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size " << width << "," << height
     << " font 'DejaVu Sans,13' linewidth 1.6\n"
     << "set output 'plot.png'\nset multiplot\n"
     << "set label 1001 " << GnuplotQuoted(title) << " at screen 0.5, screen " << 1 - 35.0 / height
     << " center font ',16'\n"
     << "set label 1002 " << GnuplotQuoted(subtitle) << " at screen 0.5, screen "
     << 1 - 62.0 / height << " center font ',11' tc rgb '#444444'\n"
     << "set border lw 1\nset tics out nomirror\nset mxtics 2\nset mytics 2\nunset key\n"
     << "set grid xtics ytics mxtics mytics lt 1 lw 0.8 lc rgb '#dcdcdc', lt 1 lw 0.6 lc rgb "
        "'#f0f0f0'\n";
  return gp.str();
}

std::string Margins(double left, double right, double bottom, double top) {
  std::ostringstream gp;
  gp << std::setprecision(6) << "set lmargin at screen " << left << "\nset rmargin at screen "
     << right << "\nset bmargin at screen " << bottom << "\nset tmargin at screen " << top << "\n";
  return gp.str();
}

// An empty plot whose key is the only thing drawn, between screen heights bottom and top.
std::string Legend(const std::vector<PlottedEstimate>& est, bool with_gt, double bottom,
                   double top) {
  std::ostringstream gp;
  gp << "unset label 1001\nunset label 1002\nunset title\nunset xlabel\nunset ylabel\n"
     << "unset border\nunset tics\nunset grid\n"
     << Margins(0.03, 0.97, bottom, top) << "set xrange [0:1]\nset yrange [0:1]\n"
     << "set key center center horizontal box lc rgb '#bbbbbb' samplen 3 width 2 font ',12'\n"
     << "plot ";
  if (with_gt) gp << "NaN " << kGtStyle << " title 'ground truth', ";
  for (size_t k = 0; k < est.size(); ++k)
    if (est[k].ate.success)
      gp << "NaN " << EstimateStyle(k) << " title " << GnuplotQuoted(est[k].name) << ", ";
  gp << "NaN notitle\nunset multiplot\n";
  return gp.str();
}

// "aligned: se3 (rigid)"; names the estimates left out.
std::string Subtitle(const std::vector<PlottedEstimate>& est, const std::string& what) {
  std::string s = what;
  if (!est.empty()) s += "   alignment: " + std::string(AlignmentName(est.front().ate.align));
  for (const PlottedEstimate& e : est)
    if (!e.ate.success) s += "   not drawn: " + e.name + " (" + e.ate.reason + ")";
  return s;
}

double FirstTime(const std::vector<StampedPose>& gt) {
  if (gt.empty()) throw std::runtime_error("plot: the ground truth has no poses");
  return gt.front().timestamp;
}

}  // namespace

void EvaluationPlotOptions::Check() const {
  if (gnuplot.empty())
    throw std::invalid_argument("EvaluationPlotOptions.gnuplot must not be empty");
}

void PlotTrajectories(const std::vector<StampedPose>& gt,
                      const std::vector<PlottedEstimate>& estimates, double t_offset_s,
                      const std::string& png_path, const EvaluationPlotOptions& options) {
  options.Check();
  const double t0 = FirstTime(gt);
  std::vector<std::pair<std::string, std::string>> files = {{"gt.dat", PoseRows(gt, t0)}};
  std::vector<Eigen::Vector3d> all;
  all.reserve(gt.size());
  for (const StampedPose& p : gt) all.push_back(p.world_from_cam.translation());
  for (size_t k = 0; k < estimates.size(); ++k) {
    if (!estimates[k].ate.success) continue;
    const std::vector<StampedPose> aligned = AlignedPoses(estimates[k], t_offset_s);
    for (const StampedPose& p : aligned) all.push_back(p.world_from_cam.translation());
    files.push_back({"e" + std::to_string(k) + ".dat", PoseRows(aligned, t0)});
  }
  const int width = 1300, height = 720;
  std::ostringstream gp;
  gp << std::setprecision(9)
     << Header(options, width, height, Subtitle(estimates, "frame: ground truth"));
  // Two square panels of the same size in pixels, each with the same span in metres on both
  // axes: equal scale.
  const double aspect = double(height) / width;
  const double panel_w = std::min(0.41, 0.68 * aspect), panel_h = panel_w / aspect;
  const struct {
    const char* title;
    const char* ylabel;
    int axis;  // the vertical coordinate: 1 = y, 2 = z
  } panels[] = {{"x-y plane", "y [m]", 1}, {"x-z plane", "z [m]", 2}};
  for (int k = 0; k < 2; ++k) {
    const int v = panels[k].axis;
    Eigen::Vector2d lo(all.front().x(), all.front()(v)), hi = lo;
    for (const Eigen::Vector3d& p : all) {
      lo = lo.cwiseMin(Eigen::Vector2d(p.x(), p(v)));
      hi = hi.cwiseMax(Eigen::Vector2d(p.x(), p(v)));
    }
    const double span = std::max(0.05, (hi - lo).maxCoeff()) * 1.2;
    const Eigen::Vector2d mid = 0.5 * (lo + hi);
    const double centre = 0.27 + 0.5 * k;
    gp << Margins(centre - panel_w / 2, centre + panel_w / 2, 0.10, 0.10 + panel_h) << "set title "
       << GnuplotQuoted(panels[k].title) << " font ',14'\n"
       << "set xlabel 'x [m]'\nset ylabel " << GnuplotQuoted(panels[k].ylabel) << "\n"
       << "set xrange [" << mid.x() - span / 2 << ":" << mid.x() + span / 2 << "]\n"
       << "set yrange [" << mid.y() - span / 2 << ":" << mid.y() + span / 2 << "]\n";
    const std::string u = " using 2:" + std::to_string(2 + v) + " ";
    gp << "plot 'gt.dat'" << u << kGtStyle;
    for (size_t e = 0; e < estimates.size(); ++e)
      if (estimates[e].ate.success) gp << ", 'e" << e << ".dat'" << u << EstimateStyle(e);
    gp << "\n";
  }
  gp << Legend(estimates, true, 0.10 + panel_h + 0.065, 0.10 + panel_h + 0.115);
  RenderGnuplot(options.gnuplot, gp.str(), files, png_path);
}

void PlotErrors(const std::vector<StampedPose>& gt, const std::vector<PlottedEstimate>& estimates,
                const std::string& png_path, const EvaluationPlotOptions& options) {
  options.Check();
  const double t0 = FirstTime(gt);
  std::vector<std::pair<std::string, std::string>> files;
  std::ostringstream what;
  what << std::fixed << std::setprecision(4) << "ATE of every matched pose";
  for (size_t k = 0; k < estimates.size(); ++k) {
    const AteResult& ate = estimates[k].ate;
    if (!ate.success) continue;
    std::ostringstream rows;
    rows << std::setprecision(9);
    for (size_t i = 0; i < ate.pose_times_s.size(); ++i)
      rows << ate.pose_times_s[i] - t0 << ' ' << ate.pose_errors_m[i] << '\n';
    files.push_back({"err" + std::to_string(k) + ".dat", rows.str()});
    what << "   " << estimates[k].name << ": rmse " << ate.error_m.rmse << " m";
  }
  const int width = 1300, height = 560;
  std::ostringstream gp;
  gp << Header(options, width, height, Subtitle(estimates, what.str()))
     << Margins(0.10, 0.97, 0.13, 0.77)
     << "set xlabel 'time from the first ground truth pose [s]'\n"
     << "set ylabel 'ATE [m]'\nset yrange [0:*]\n";
  gp << "plot ";
  bool any = false;
  for (size_t k = 0; k < estimates.size(); ++k) {
    if (!estimates[k].ate.success) continue;
    gp << (any ? ", " : "") << "'err" << k << ".dat' using 1:2 " << EstimateStyle(k);
    any = true;
  }
  if (!any) gp << "NaN notitle";
  gp << "\n" << Legend(estimates, false, 0.80, 0.86);
  RenderGnuplot(options.gnuplot, gp.str(), files, png_path);
}

void PlotPosesOverTime(const std::vector<StampedPose>& gt,
                       const std::vector<PlottedEstimate>& estimates, double t_offset_s,
                       const std::string& png_path, const EvaluationPlotOptions& options) {
  options.Check();
  const double t0 = FirstTime(gt);
  std::vector<std::pair<std::string, std::string>> files = {{"gt.dat", PoseRows(gt, t0)}};
  for (size_t k = 0; k < estimates.size(); ++k)
    if (estimates[k].ate.success)
      files.push_back(
          {"e" + std::to_string(k) + ".dat", PoseRows(AlignedPoses(estimates[k], t_offset_s), t0)});
  const int width = 1300, height = 950;
  std::ostringstream gp;
  gp << Header(options, width, height,
               Subtitle(estimates, "frame: ground truth; angles: R = Rz(yaw) Ry(pitch) Rx(roll)"));
  const char* const labels[] = {"x [m]",      "y [m]",       "z [m]",
                                "roll [deg]", "pitch [deg]", "yaw [deg]"};
  // Three rows of two panels between screen heights 0.07 and 0.84.
  const double row_h = 0.77 / 3;
  for (int k = 0; k < 6; ++k) {
    const int col = k / 3, row = k % 3;
    const double top = 0.84 - row * row_h;
    gp << Margins(0.09 + 0.5 * col, 0.47 + 0.5 * col, top - row_h + 0.045, top) << "set ylabel "
       << GnuplotQuoted(labels[k]) << "\n"
       << (row == 2 ? "set xlabel 'time [s]'\n" : "unset xlabel\n");
    const std::string u = " using 1:" + std::to_string(2 + k) + " ";
    gp << "plot 'gt.dat'" << u << kGtStyle;
    for (size_t e = 0; e < estimates.size(); ++e)
      if (estimates[e].ate.success) gp << ", 'e" << e << ".dat'" << u << EstimateStyle(e);
    gp << "\n";
  }
  gp << Legend(estimates, true, 0.855, 0.905);
  RenderGnuplot(options.gnuplot, gp.str(), files, png_path);
}

std::string PlotEvaluation(const std::vector<EvaluationReport>& reports,
                           const EvaluationFigures& figures, const EvaluationPlotOptions& options) {
  options.Check();
  if (reports.empty() ||
      (figures.trajectories.empty() && figures.errors.empty() && figures.poses.empty()))
    return "";
  const std::vector<StampedPose> gt = ReadTrajectory(reports.front().groundtruth_path).poses;
  std::vector<PlottedEstimate> estimates;
  estimates.reserve(reports.size());
  for (const EvaluationReport& r : reports)
    estimates.push_back({r.estimate_path, ReadTrajectory(r.estimate_path).poses, r.ate});
  const double t_offset_s = reports.front().options.t_offset_s;
  std::string written;
  if (!figures.trajectories.empty()) {
    PlotTrajectories(gt, estimates, t_offset_s, figures.trajectories, options);
    written += "wrote " + figures.trajectories + ": trajectories in the ground truth's frame\n";
  }
  if (!figures.errors.empty()) {
    PlotErrors(gt, estimates, figures.errors, options);
    written += "wrote " + figures.errors + ": ATE of every matched pose over time\n";
  }
  if (!figures.poses.empty()) {
    PlotPosesOverTime(gt, estimates, t_offset_s, figures.poses, options);
    written += "wrote " + figures.poses + ": x, y, z, roll, pitch, yaw over time\n";
  }
  return written;
}

}  // namespace rgbdvo
