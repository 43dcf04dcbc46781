// Trajectory figures through gnuplot.
#include "rgbdvo/evaluation/plot.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

std::vector<StampedPose> Circle(double radius, const Rigid3d& world_from_path) {
  std::vector<StampedPose> out;
  for (int k = 0; k < 60; ++k) {
    const double a = 2 * M_PI * k / 60;
    Rigid3d T = Rigid3d::Identity();
    T.translation() =
        Eigen::Vector3d(radius * std::cos(a), 0.1 * std::sin(3 * a), radius * std::sin(a));
    out.push_back({0.1 * k, world_from_path * T});
  }
  return out;
}

}  // namespace

TEST_CASE("PlotTrajectory writes a PNG of the requested size with the aligned ground truth") {
  std::mt19937 rng(2);
  const std::vector<StampedPose> est = Circle(1.0, Rigid3d::Identity());
  const std::vector<StampedPose> gt = Circle(1.0, RandomRigid(rng, 1.0, 2.0));
  const std::string png = MakeTempDir("plot") + "/sub/figure.png";  // folder is created
  PlotOptions options;
  options.title = "test circle";
  const PlotResult r = PlotTrajectory(est, gt, png, options);
  CHECK(r.aligned);
  CHECK(r.ate.matched == 60);
  CHECK(r.ate.error_m.rmse < 1e-9);  // gt is est moved rigidly
  CHECK_THAT(r.Brief(), Catch::Contains("60 poses matched with ground truth"));
  CHECK(PngSize(png) == std::make_pair(options.width_px, options.height_px));
  // A drawn figure (axes, text, two paths) compresses to tens of kB; an empty canvas to ~5 kB.
  CHECK(std::filesystem::file_size(png) > 20000);
}

TEST_CASE("PlotTrajectory without ground truth, or with none matching, draws the estimate") {
  const std::vector<StampedPose> est = Circle(0.5, Rigid3d::Identity());
  const std::string dir = MakeTempDir("plot");
  PlotResult r = PlotTrajectory(est, {}, dir + "/a.png", {});
  CHECK_FALSE(r.aligned);
  CHECK(PngSize(dir + "/a.png").first == PlotOptions().width_px);
  std::vector<StampedPose> late = est;
  for (StampedPose& p : late) p.timestamp += 100;
  r = PlotTrajectory(est, late, dir + "/b.png", {});
  CHECK_FALSE(r.aligned);
  CHECK_THAT(r.Brief(), Catch::Contains("not drawn"));
  CHECK(PngSize(dir + "/b.png").first == PlotOptions().width_px);
}

TEST_CASE("PlotTrajectory: a missing gnuplot is a clear error") {
  PlotOptions options;
  options.gnuplot = "/nonexistent/gnuplot";
  CHECK_THROWS_WITH(
      PlotTrajectory(Circle(1, Rigid3d::Identity()), {}, MakeTempDir("plot") + "/c.png", options),
      Catch::Contains("/nonexistent/gnuplot") && Catch::Contains("gnuplot-nox"));
}

TEST_CASE("PlotTrajectory: hostile titles and paths run nothing and the plot is still written") {
  const std::string dir = MakeTempDir("plot");
  const std::string marker = dir + "/pwned";  // what an injected command would create
  const std::string run = "touch " + marker;
  const std::vector<std::string> hostile = {
      "x`" + run + "`y",
      "$(" + run + ")",
      "q'uote\"s",
      "line\nset output '" + dir + "/evil.png'",
      "system(\"" + run + "\") and system('" + run + "')",
      "@macro \\ back\\slash",
  };
  int k = 0;
  for (const std::string& text : hostile) {
    CAPTURE(text);
    PlotOptions options;
    options.title = text;
    // The same text in a file name (a '/' would make it a folder: replaced).
    std::string name = text;
    std::replace(name.begin(), name.end(), '/', '_');
    const std::string png = dir + "/" + std::to_string(k++) + name + ".png";
    PlotTrajectory(Circle(1, Rigid3d::Identity()), {}, png, options);
    CHECK(PngSize(png).first == options.width_px);
    CHECK_FALSE(std::filesystem::exists(marker));
    CHECK_FALSE(std::filesystem::exists(dir + "/evil.png"));
  }
}

TEST_CASE("PlotTrajectory leaves no temporary files, also when gnuplot fails") {
  const std::string tmp = MakeTempDir("plot_tmpdir"), out = MakeTempDir("plot");
  const char* old = std::getenv("TMPDIR");
  const std::string saved = old ? old : "";
  setenv("TMPDIR", tmp.c_str(), 1);  // NOLINT(concurrency-mt-unsafe): no other thread runs here
  PlotTrajectory(Circle(1, Rigid3d::Identity()), {}, out + "/a.png", {});
  PlotOptions failing;
  failing.gnuplot = "false";  // starts, exits 1
  CHECK_THROWS_WITH(PlotTrajectory(Circle(1, Rigid3d::Identity()), {}, out + "/b.png", failing),
                    Catch::Contains("failed (exit 1)") && Catch::Contains("b.png"));
  if (old)
    setenv("TMPDIR", saved.c_str(), 1);  // NOLINT(concurrency-mt-unsafe): no other thread runs here
  else
    unsetenv("TMPDIR");  // NOLINT(concurrency-mt-unsafe): no other thread runs here
  CHECK(std::filesystem::is_empty(tmp));
}

TEST_CASE("PlotTrajectory counts a repeated timestamp once, as rgbdvo eval reads the file") {
  // A ground truth sampled twice as often as the estimate, and an estimate with two poses at one
  // time (stamped by a depth image two colour frames share): the last one is kept, as when the
  // file is read back, not matched a second time to the ground truth pose 0.01 s later.
  const std::vector<StampedPose> est = Circle(1.0, Rigid3d::Identity());
  std::vector<StampedPose> gt = est;
  for (const StampedPose& p : est) gt.push_back({p.timestamp + 0.01, p.world_from_cam});
  KeepLastOfEachTime(&gt);
  std::vector<StampedPose> repeated = est;
  repeated.insert(repeated.begin() + 10, {est[10].timestamp, Rigid3d::Identity()});
  const PlotResult r = PlotTrajectory(repeated, gt, MakeTempDir("plot") + "/r.png", {});
  CHECK(r.estimate_poses == 60);
  CHECK(r.ate.matched == 60);
  CHECK(r.ate.error_m.max < 1e-9);
  CHECK_THAT(r.Brief(), Catch::Contains("estimate 60 poses, 60 poses matched"));
}
