// The reports of `rgbdvo eval`: files read, table and JSON, one estimate or several.
#include "rgbdvo/evaluation/evaluation_report.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// 50 poses 0.1 s apart on a curve that is not planar, turning as it goes.
std::vector<StampedPose> CurvyPath() {
  std::vector<StampedPose> out;
  for (int k = 0; k < 50; ++k) {
    const double t = 0.1 * k;
    Rigid3d T = Rigid3d::Identity();
    T.linear() = AxisAngle(Eigen::Vector3d::UnitZ(), 0.3 * std::sin(t));
    T.translation() = Eigen::Vector3d(std::cos(t), std::sin(2 * t), 0.3 * t);
    out.push_back({100.0 + t, T});
  }
  return out;
}

// The positions multiplied by c about the origin.
std::vector<StampedPose> Scaled(std::vector<StampedPose> poses, double c) {
  for (StampedPose& p : poses) p.world_from_cam.translation() *= c;
  return poses;
}

// The whitespace-separated fields of the table line that starts with `name`.
std::vector<std::string> Row(const std::string& table, const std::string& name) {
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(name + " ", 0) != 0) continue;
    std::istringstream fields(line);
    std::vector<std::string> out;
    for (std::string f; fields >> f;) out.push_back(f);
    return out;
  }
  return {};
}

}  // namespace

TEST_CASE("Evaluation refuses no overlap and bad options, and reports too short runs") {
  const std::string dir = MakeTempDir("eval");
  std::ofstream(dir + "/gt.txt") << "1 0 0 0 0 0 0 1\n1.1 0 0 0 0 0 0 1\n1.2 0 0 0 0 0 0 1\n";
  std::ofstream(dir + "/est.txt") << "5 0 0 0 0 0 0 1\n5.1 0 0 0 0 0 0 1\n";
  CHECK_THROWS_WITH(EvaluateFiles(dir + "/gt.txt", dir + "/est.txt", {}),
                    Catch::Contains("no overlapping timestamps") && Catch::Contains("est.txt"));

  EvaluationOptions bad;
  bad.delta = -1;
  CHECK_THROWS_WITH(bad.Check(), Catch::Contains("delta"));

  // Same three poses: ATE works, RPE has no pair 1 s apart.
  const EvaluationReport r = EvaluateFiles(dir + "/gt.txt", dir + "/gt.txt", {});
  CHECK(r.ate.success);
  CHECK_FALSE(r.rpe.success);
  CHECK_THAT(r.Table(), Catch::Contains("n/a"));
  CHECK_THAT(r.Json(), Catch::Contains("\"rpe\": {\"success\": false"));
  // What could not be computed is null, never a perfect 0; what was computed is a number.
  CHECK_THAT(r.Json(), Catch::Contains("\"trans_m\": {\"rmse\": null, \"mean\": null, "
                                       "\"median\": null, \"max\": null}"));
  CHECK_THAT(r.Json(), Catch::Contains("\"rot_deg\": {\"rmse\": null"));
  CHECK_THAT(r.Json(), Catch::Contains("\"error_m\": {\"rmse\": 0"));
}

TEST_CASE("Several estimates: one row each, JSON has null where nothing was computed") {
  const std::string dir = MakeTempDir("eval_multi");
  const std::vector<StampedPose> gt = CurvyPath();
  WriteTumTrajectory(dir + "/gt.txt", gt);
  WriteTumTrajectory(dir + "/half.txt", Scaled(gt, 0.5));
  WriteTumTrajectory(dir + "/short.txt", {gt.begin(), gt.begin() + 2});
  EvaluationOptions o;
  o.align = Alignment::kSim3;
  std::vector<EvaluationReport> reports;
  for (const char* name : {"/gt.txt", "/half.txt", "/short.txt"})
    reports.push_back(EvaluateFiles(dir + "/gt.txt", dir + name, o));
  CHECK(reports[1].ate.scale == Approx(2.0).epsilon(1e-6));
  const std::string table = ComparisonTable(reports);
  INFO(table);
  CHECK_THAT(table, Catch::Contains("alignment sim3"));
  using Fields = std::vector<std::string>;
  CHECK(Row(table, dir + "/gt.txt") == Fields{dir + "/gt.txt", "50", "50", "1.0000", "0.0000",
                                              "0.0000", "0.0000", "0.0000", "39", "0.0000",
                                              "0.000"});
  const Fields half = Row(table, dir + "/half.txt");
  REQUIRE(half.size() == 11);
  CHECK(Fields(half.begin() + 1, half.begin() + 4) == Fields{"50", "50", "2.0000"});
  CHECK(Row(table, dir + "/short.txt") ==
        Fields{dir + "/short.txt", "2", "2", "n/a", "n/a", "0", "n/a", "n/a"});
  CHECK_THAT(table, Catch::Contains("need 3"));
  const std::string json = ComparisonJson(reports);
  CHECK_THAT(json, Catch::StartsWith("[{\"groundtruth\": ") && Catch::EndsWith("}]\n"));
  CHECK_THAT(json, Catch::Contains("\"matched\": 2, \"aligned_on\": 0, \"scale\": null"));
  CHECK_THAT(json, Catch::Contains("\"align\": \"sim3\""));
}

TEST_CASE("Coordinates too large to compute with give n/a and a reason, JSON null, never inf") {
  const std::string dir = MakeTempDir("eval_huge");
  const std::vector<StampedPose> gt = CurvyPath();
  WriteTumTrajectory(dir + "/gt.txt", gt);
  // One row at 1e308 m, and every row at 1e200 m: errors whose squares overflow.
  std::ofstream(dir + "/far.txt") << "100.0 1e308 0 0 0 0 0 1\n";
  {
    std::ofstream far(dir + "/far.txt", std::ios::app);
    for (size_t k = 1; k < gt.size(); ++k) WriteTumLine(far, gt[k].timestamp, gt[k].world_from_cam);
  }
  WriteTumTrajectory(dir + "/big.txt", Scaled(gt, 1e200));
  EvaluationOptions none;
  none.align = Alignment::kNone;
  for (const auto& [name, options] :
       {std::make_pair("/far.txt", EvaluationOptions()), std::make_pair("/big.txt", none)}) {
    const EvaluationReport report = EvaluateFiles(dir + "/gt.txt", dir + name, options);
    // The folder's random name left out: it may hold the letters looked for.
    const auto text = [&](std::string t) {
      for (size_t at; (at = t.find(dir)) != std::string::npos;) t.replace(at, dir.size(), "DIR");
      return t;
    };
    const std::string json = text(report.Json()), table = text(report.Table());
    INFO(name << "\n" << json << table);
    CHECK_THAT(json, !Catch::Contains("inf") && !Catch::Contains("nan"));
    CHECK_THAT(table, !Catch::Contains("inf") && !Catch::Contains("nan"));
    CHECK(!report.ate.success);
    CHECK_THAT(report.ate.reason, Catch::Contains("not finite"));
    CHECK_THAT(json, Catch::Contains("\"error_m\": {\"rmse\": null") &&
                         Catch::Contains("\"reason\": \"position error"));
    CHECK_THAT(table, Catch::Contains("n/a (position error"));
    CHECK_THAT(text(ComparisonTable({report})), !Catch::Contains("inf") && !Catch::Contains("nan"));
  }
  // Options printed in the JSON are finite too.
  EvaluationOptions bad;
  bad.max_dt_s = INFINITY;
  CHECK_THROWS_WITH(bad.Check(), Catch::Contains("max_dt_s"));
  bad = EvaluationOptions();
  bad.delta = INFINITY;
  CHECK_THROWS_WITH(bad.Check(), Catch::Contains("delta"));
}
