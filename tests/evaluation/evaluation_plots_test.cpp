// The figures of an evaluation through gnuplot.
#include "rgbdvo/evaluation/evaluation_plots.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// A helix, 0.1 s a pose, turning as it goes.
std::vector<StampedPose> Helix() {
  std::vector<StampedPose> out;
  for (int k = 0; k < 80; ++k) {
    const double a = 2 * M_PI * k / 60;
    Rigid3d T = Rigid3d::Identity();
    T.linear() = AxisAngle(Eigen::Vector3d::UnitZ(), a);
    T.translation() = Eigen::Vector3d(std::cos(a), std::sin(a), 0.01 * k);
    out.push_back({100 + 0.1 * k, T});
  }
  return out;
}

}  // namespace

TEST_CASE("The evaluation figures are written at their sizes, a failed estimate left out") {
  const std::vector<StampedPose> gt = Helix();
  std::mt19937 rng(3);
  const Rigid3d moved = RandomRigid(rng, 1.0, 1.0);
  std::vector<StampedPose> est = gt, late = gt;
  for (StampedPose& p : est) p.world_from_cam = moved * p.world_from_cam;
  for (StampedPose& p : late) p.timestamp += 1000;  // nothing matches: no ATE
  const std::vector<PlottedEstimate> estimates = {
      {"moved", est, ComputeAte(gt, est, {})},
      {"x`touch pwned`'\"", est, ComputeAte(gt, est, {})},  // a hostile name stays text
      {"late", late, ComputeAte(gt, late, {})}};
  REQUIRE_FALSE(estimates[2].ate.success);
  const std::string dir = MakeTempDir("eval_plots");
  EvaluationPlotOptions options;
  options.title = "helix";
  PlotTrajectories(gt, estimates, 0, dir + "/t.png", options);
  PlotErrors(gt, estimates, dir + "/e.png", options);
  PlotPosesOverTime(gt, estimates, 0, dir + "/p.png", options);
  CHECK(PngSize(dir + "/t.png") == std::make_pair(1300, 720));
  CHECK(PngSize(dir + "/e.png") == std::make_pair(1300, 560));
  CHECK(PngSize(dir + "/p.png") == std::make_pair(1300, 950));
  // Drawn figures (axes, text, lines) compress to tens of kB; an empty canvas to a few.
  for (const char* name : {"/t.png", "/e.png", "/p.png"})
    CHECK(std::filesystem::file_size(dir + name) > 20000);
  CHECK_FALSE(std::filesystem::exists(dir + "/pwned"));

  options.gnuplot = "/nonexistent/gnuplot";
  CHECK_THROWS_WITH(PlotErrors(gt, estimates, dir + "/x.png", options),
                    Catch::Contains("not found"));
}
