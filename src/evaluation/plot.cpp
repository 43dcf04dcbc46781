#include "rgbdvo/evaluation/plot.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/util/temp_dir.hpp"

namespace rgbdvo {
namespace {

namespace fs = std::filesystem;

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

// A gnuplot single-quoted string: gnuplot expands nothing inside single quotes (no backquote
// command substitution, no @macros, no backslash escapes), a quote is written twice, and control
// characters (newlines end a command) become spaces. Our strings (paths, titles, reasons) thus
// stay text, whatever a user or a recording's name puts in them.
std::string Quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\'')
      out += "''";
    else
      out += (byte < 0x20 || byte == 0x7f) ? ' ' : c;
  }
  return out + "'";
}

// Runs `program script` in `dir` with stderr into `err_path` and no shell in between: the
// program's name and the paths reach exec() as they are. Returns the exit code, 127 when the
// program cannot be started, -1 when it did not exit normally.
int RunInFolder(const std::string& program, const fs::path& dir, const std::string& script,
                const fs::path& err_path) {
  // Everything the child needs is prepared before fork(): after it only async-signal-safe calls.
  const std::string dir_s = dir.string(), err_s = err_path.string();
  std::vector<char*> argv = {const_cast<char*>(program.c_str()), const_cast<char*>(script.c_str()),
                             nullptr};
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("plot: cannot start " + program);
  if (pid == 0) {
    const int err = open(err_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int in = open("/dev/null", O_RDONLY);
    if (err < 0 || in < 0 || dup2(err, 2) < 0 || dup2(in, 0) < 0 || chdir(dir_s.c_str()) != 0)
      _exit(126);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void WritePoints(const fs::path& path, const std::vector<Eigen::Vector3d>& points) {
  std::ofstream out(path);
  out << std::setprecision(9);
  for (const Eigen::Vector3d& p : points) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  if (!out) throw std::runtime_error(path.string() + ": cannot write plot data");
}

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
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

  const ScopedTempDir scoped_tmp("rgbdvo_plot_");
  const fs::path tmp = scoped_tmp.path();
  WritePoints(tmp / "est.dat", est);
  WritePoints(tmp / "gt.dat", gt);
  WritePoints(tmp / "start.dat", {est.front()});
  WritePoints(tmp / "end.dat", {est.back()});

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
     << "set label 1001 " << Quoted(title) << " at screen 0.5, screen 0.965 center font ',16'\n"
     << "set label 1002 " << Quoted(subtitle)
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
       << "set title " << Quoted(panel.title) << " font ',14'\n"
       << "set xlabel " << Quoted(panel.xlabel) << "\nset ylabel " << Quoted(panel.ylabel) << "\n"
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
  {
    std::ofstream out(tmp / "plot.gp");
    out << gp.str();
    if (!out) throw std::runtime_error((tmp / "plot.gp").string() + ": cannot write");
  }
  // gnuplot writes into our temporary folder; the image is then copied to where the user asked,
  // so the user's path never enters the script.
  const int code = RunInFolder(options.gnuplot, tmp, "plot.gp", tmp / "err.txt");
  if (code == 127)
    throw std::runtime_error("plot: '" + options.gnuplot +
                             "' not found; install the Debian package gnuplot-nox "
                             "(scripts/setup.sh does)");
  if (code != 0) {
    std::string err = ReadAll(tmp / "err.txt");
    std::replace(err.begin(), err.end(), '\n', ' ');
    throw std::runtime_error("plot: " + options.gnuplot + " failed (exit " + std::to_string(code) +
                             ") writing " + png_path + ": " + err.substr(0, 300));
  }
  std::error_code ec;
  const fs::path image = tmp / "plot.png";
  if (!fs::exists(image, ec) || fs::file_size(image, ec) == 0)
    throw std::runtime_error("plot: " + png_path + ": gnuplot wrote no image");
  const fs::path parent = fs::path(png_path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);  // a failure shows in the copy
  fs::copy_file(image, png_path, fs::copy_options::overwrite_existing, ec);
  if (ec) throw std::runtime_error("plot: " + png_path + ": " + ec.message());
  return result;
}

}  // namespace rgbdvo
