#include "rgbdvo/odometry/odometry_parameters.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

using namespace rgbdvo;

namespace {

// The address a parameter names inside `o`, as an integer offset, to compare parameters.
std::ptrdiff_t Offset(const OdometryParameter& p, OdometryOptions& o) {
  return std::visit(
      [&](auto* field) {
        return reinterpret_cast<const char*>(field) - reinterpret_cast<const char*>(&o);
      },
      p.field(o));
}

}  // namespace

TEST_CASE("Every odometry parameter has one key, one flag and a field of its own") {
  OdometryOptions o;
  std::set<std::string> keys, flags;
  std::set<std::ptrdiff_t> fields;
  for (const OdometryParameter& p : OdometryParameters()) {
    INFO(p.key);
    CHECK(keys.insert(p.key).second);
    CHECK(flags.insert(p.flag).second);
    CHECK(fields.insert(Offset(p, o)).second);
    CHECK(std::string(p.help).size() > 10);
    CHECK(FindParameter(p.key) == &p);
  }
  CHECK(FindParameter("no.such_key") == nullptr);
  // The printed configuration is the list: one line per parameter, in its order.
  std::istringstream printed(o.ToString());
  size_t i = 0;
  for (std::string line; std::getline(printed, line); ++i) {
    REQUIRE(i < OdometryParameters().size());
    CHECK(line ==
          std::string(OdometryParameters()[i].key) + " = " + OdometryParameters()[i].Get(o));
  }
  CHECK(i == OdometryParameters().size());
}

TEST_CASE("Every number parameter has a bounded range holding both presets' values") {
  const auto holds = [](const ParameterRange& r, const std::string& value) {
    const double v = std::stod(value);
    return v >= r.min && v <= r.max;
  };
  const OdometryOptions defaults, paper = PresetOptions("paper");
  int numbers = 0;
  for (const OdometryParameter& p : OdometryParameters()) {
    INFO(p.key << " in " << FormatRange(p.range));
    if (!p.IsNumber()) continue;
    ++numbers;
    CHECK(p.range.Bounded());
    CHECK(holds(p.range, p.Get(defaults)));
    CHECK(holds(p.range, p.Get(paper)));
  }
  CHECK(numbers > 30);
}

TEST_CASE("A number outside its parameter's range is refused naming the parameter and range") {
  OdometryOptions o;
  const OdometryParameter* window = FindParameter("tracking.window_px");
  REQUIRE(window != nullptr);
  CHECK_THROWS_WITH(window->Set("20001", &o), Catch::Contains("tracking.window_px") &&
                                                  Catch::Contains("20001") &&
                                                  Catch::Contains("[3, 101]"));
  CHECK_THROWS_WITH(window->Set("2", &o), Catch::Contains("[3, 101]"));
  window->Set("101", &o);  // both ends are in the range
  CHECK(o.tracking.window_px == 101);
  window->Set("3", &o);
  CHECK(o.tracking.window_px == 3);
  CHECK_THROWS_WITH(FindParameter("features.contrast_threshold")->Set("nan", &o),
                    Catch::Contains("features.contrast_threshold"));
  std::istringstream config("tracking.window_px = 100001\n");
  CHECK_THROWS_WITH(ApplyConfig(config, "x.conf", &o),
                    Catch::Contains("x.conf:1") && Catch::Contains("[3, 101]"));
}

TEST_CASE("A parameter set from text reads back as the same text, for every type") {
  OdometryOptions o;
  FindParameter("matching.ratio")->Set("0.65", &o);
  CHECK(o.matching.ratio == 0.65);
  FindParameter("ransac.max_trials")->Set(" 321 ", &o);
  CHECK(o.ransac.max_trials == 321);
  FindParameter("seed")->Set("4000000000", &o);
  CHECK(o.seed == 4000000000u);
  FindParameter("matching.mutual")->Set("no", &o);
  CHECK_FALSE(o.matching.mutual);
  FindParameter("matching.mutual")->Set("TRUE", &o);
  CHECK(o.matching.mutual);
  FindParameter("features.implementation")->Set("opencv", &o);
  CHECK(o.features.implementation == SiftImplementation::kOpenCv);
  CHECK(FindParameter("features.implementation")->Get(o) == "opencv");
  FindParameter("motion.model")->Set("planar", &o);
  FindParameter("motion.floor")->Set("accelerometer", &o);
  CHECK(o.motion.planar());
  CHECK(o.motion.floor == FloorSource::kAccelerometer);
  CHECK(o.NeedsAccelerometer());
  FindParameter("refine.depth_noise_coeff")->Set("0.001425", &o);
  CHECK(FindParameter("refine.depth_noise_coeff")->Get(o) == "0.001425");
  CHECK(FindParameter("matching.mutual")->Get(o) == "true");
}

TEST_CASE("A value of the wrong type is refused naming the parameter") {
  OdometryOptions o;
  CHECK_THROWS_WITH(FindParameter("ransac.max_trials")->Set("2.5", &o),
                    Catch::Contains("ransac.max_trials") && Catch::Contains("'2.5'"));
  CHECK_THROWS_WITH(FindParameter("seed")->Set("-1", &o), Catch::Contains("seed"));
  CHECK_THROWS_WITH(FindParameter("matching.ratio")->Set("abc", &o),
                    Catch::Contains("matching.ratio") && Catch::Contains("not a number"));
  CHECK_THROWS_WITH(FindParameter("matching.mutual")->Set("maybe", &o),
                    Catch::Contains("true or false"));
  CHECK_THROWS(FindParameter("features.implementation")->Set("  ", &o));
  CHECK_THROWS_WITH(FindParameter("motion.model")->Set("3dof", &o),
                    Catch::Contains("motion.model") && Catch::Contains("one of 6dof, planar"));
  CHECK(o.ransac.max_trials == OdometryOptions{}.ransac.max_trials);  // unchanged
}

TEST_CASE("A printed configuration read as a configuration file gives the same options") {
  const OdometryOptions paper = PresetOptions("paper");
  OdometryOptions o;  // the default
  std::istringstream file("# a comment\n\n" + paper.ToString());
  ApplyConfig(file, "paper.cfg", &o);
  CHECK(o.ToString() == paper.ToString());
  CHECK(o.ToString() != OdometryOptions{}.ToString());
}

TEST_CASE("A configuration file changes only the keys it names, in file order") {
  OdometryOptions o;
  std::istringstream file(
      "ransac.max_trials = 50   # fewer\nmatching.mutual=false\nransac.max_trials = 60\n");
  ApplyConfig(file, "f.cfg", &o);
  CHECK(o.ransac.max_trials == 60);
  CHECK_FALSE(o.matching.mutual);
  OdometryOptions expected;
  expected.ransac.max_trials = 60;
  expected.matching.mutual = false;
  CHECK(o.ToString() == expected.ToString());
}

TEST_CASE("Every key is its field's path, renamed keys of earlier files still load") {
  // A key names the field it sets: set through the key, the field's value changes.
  OdometryOptions o;
  FindParameter("guided_radius_px")->Set("12", &o);
  FindParameter("track_stale_noise_ratio")->Set("2", &o);
  CHECK(o.guided_radius_px == 12);
  CHECK(o.track_stale_noise_ratio == 2);
  std::istringstream old(
      "matching.guided_rematch = false\ntracking.enabled = false\nrefine.enabled = false\n");
  ApplyConfig(old, "old.cfg", &o);
  CHECK_FALSE(o.guided_rematch);
  CHECK_FALSE(o.track_between_keyframes);
  CHECK_FALSE(o.refine_enabled);
}

TEST_CASE("A removed parameter loads at its old default and is refused at any other value") {
  OdometryOptions o;
  std::istringstream old("tracking.fusion = false\ntracking.max_back_error_px = 0\nseed = 3\n");
  ApplyConfig(old, "old.cfg", &o);
  CHECK(o.seed == 3u);
  std::istringstream set("seed = 1\ntracking.fusion = true\n");
  CHECK_THROWS_WITH(ApplyConfig(set, "set.cfg", &o),
                    Catch::Contains("set.cfg:2") && Catch::Contains("was removed"));
}

TEST_CASE("Configuration file errors name the file and line") {
  OdometryOptions o;
  std::istringstream unknown("seed = 1\nransac.trials = 5\n");
  CHECK_THROWS_WITH(
      ApplyConfig(unknown, "f.cfg", &o),
      Catch::Contains("f.cfg:2") && Catch::Contains("unknown parameter 'ransac.trials'"));
  std::istringstream no_equals("seed 1\n");
  CHECK_THROWS_WITH(ApplyConfig(no_equals, "g.cfg", &o),
                    Catch::Contains("g.cfg:1") && Catch::Contains("key = value"));
  std::istringstream bad_value("\n\nmatching.ratio = x\n");
  CHECK_THROWS_WITH(ApplyConfig(bad_value, "h.cfg", &o),
                    Catch::Contains("h.cfg:3") && Catch::Contains("matching.ratio"));
  CHECK_THROWS_WITH(ApplyConfigFile("/nonexistent/odometry.cfg", &o),
                    Catch::Contains("/nonexistent/odometry.cfg"));
}
