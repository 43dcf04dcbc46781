#include "rgbdvo/pipeline/run_parameters.hpp"

#include <catch2/catch.hpp>
#include <set>
#include <sstream>
#include <string>

using namespace rgbdvo;

TEST_CASE("Every run parameter has a key under run., a flag and a field of its own") {
  std::set<std::string> keys, flags;
  std::set<const void*> fields;
  RunOptions r;
  for (const RunParameter& p : RunParameters()) {
    INFO(p.key);
    CHECK(std::string(p.key).rfind("run.", 0) == 0);
    CHECK(keys.insert(p.key).second);
    CHECK(flags.insert(p.flag).second);
    CHECK(fields.insert(std::visit([](auto* f) -> const void* { return f; }, p.field(r))).second);
    CHECK(FindRunParameter(p.key) == &p);
    // No flag is also an odometry parameter's.
    for (const OdometryParameter& o : OdometryParameters()) CHECK(std::string(o.flag) != p.flag);
  }
  CHECK(keys.size() == 3);
  CHECK(FindRunParameter("seed") == nullptr);
}

TEST_CASE("One configuration file sets both the odometry and the run, in file order") {
  OdometryOptions odometry;
  RunOptions run;
  std::istringstream file(
      "run.threads = 3\nseed = 7\nrun.parallel_keyframe_sift = on\nrun.threads = 2\n");
  ApplyConfig(file, "both.cfg", &odometry, &run);
  CHECK(run.threads == 2);
  CHECK(run.parallel_keyframe_sift);
  CHECK(run.queue_frames == RunOptions{}.queue_frames);
  CHECK(odometry.seed == 7u);

  // The printed configuration reads back as the same configuration.
  OdometryOptions odometry2;
  RunOptions run2;
  std::istringstream printed(ConfigurationText(odometry, run));
  ApplyConfig(printed, "printed.cfg", &odometry2, &run2);
  CHECK(ConfigurationText(odometry2, run2) == ConfigurationText(odometry, run));
  CHECK_THAT(ConfigurationText(odometry, run),
             Catch::Contains("\nrun.threads = 2\n") && Catch::Contains("\nseed = 7\n"));
}

TEST_CASE(
    "A run key is an error where only the odometry is configured, and bad values name the line") {
  OdometryOptions odometry;
  std::istringstream run_key("run.threads = 2\n");
  CHECK_THROWS_WITH(ApplyConfig(run_key, "odometry.cfg", &odometry),
                    Catch::Contains("odometry.cfg:1") && Catch::Contains("run.threads"));
  RunOptions run;
  std::istringstream bad("seed = 1\nrun.queue_frames = many\n");
  CHECK_THROWS_WITH(ApplyConfig(bad, "bad.cfg", &odometry, &run),
                    Catch::Contains("bad.cfg:2") && Catch::Contains("run.queue_frames"));
  CHECK_THROWS_WITH(ApplyConfigFile("/nonexistent/run.cfg", &odometry, &run),
                    Catch::Contains("/nonexistent/run.cfg"));
}
