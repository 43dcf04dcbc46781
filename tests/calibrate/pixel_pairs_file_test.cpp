#include "rgbdvo/calibrate/pixel_pairs_file.hpp"

#include <catch2/catch.hpp>
#include <fstream>

#include "test_support.hpp"

using namespace rgbdvo;

namespace {
std::string Write(const std::string& text) {
  static int n = 0;
  std::string path = test::MakeTempDir("pairs") + "/p" + std::to_string(n++) + ".csv";
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST_CASE("Pixel pairs file round-trips at full precision") {
  const std::vector<PixelPair> pairs = {{1.25, 2.5, 3.125, 4.0625}, {639.7, 479.3, 600.01, 450.99}};
  const std::string path = test::MakeTempDir("pairs") + "/p.csv";
  SavePixelPairs(pairs, path);
  const auto back = LoadPixelPairs(path);
  REQUIRE(back.size() == 2);
  for (size_t i = 0; i < 2; ++i) {
    CHECK(back[i].u_vis == pairs[i].u_vis);
    CHECK(back[i].v_vis == pairs[i].v_vis);
    CHECK(back[i].u_ir == pairs[i].u_ir);
    CHECK(back[i].v_ir == pairs[i].v_ir);
  }
}

TEST_CASE("Pixel pairs file skips comments, blank lines, spaces and CRLF") {
  const auto pairs = LoadPixelPairs(Write(
      "# clicked on frame 0\r\nu_vis, v_vis, u_ir, v_ir\r\n\r\n 10 , 20,30,40\r\n# x\n1,2,3,4\n"));
  REQUIRE(pairs.size() == 2);
  CHECK(pairs[0].u_vis == 10);
  CHECK(pairs[0].v_ir == 40);
  CHECK(pairs[1].u_ir == 3);
}

TEST_CASE("Pixel pairs file errors name the file and line") {
  const std::string bad_header = Write("u,v,x,y\n1,2,3,4\n");
  CHECK_THROWS_WITH(
      LoadPixelPairs(bad_header),
      Catch::StartsWith(bad_header + ":1: expected the header 'u_vis,v_vis,u_ir,v_ir'"));
  const std::string three = Write("u_vis,v_vis,u_ir,v_ir\n1,2,3,4\n1,2,3\n");
  CHECK_THROWS_WITH(LoadPixelPairs(three),
                    Catch::StartsWith(three + ":3: expected 4 comma-separated numbers"));
  const std::string five = Write("u_vis,v_vis,u_ir,v_ir\n1,2,3,4,\n");
  CHECK_THROWS_WITH(LoadPixelPairs(five),
                    Catch::Contains(":2: expected 4") && Catch::Contains("got 5"));
  const std::string word = Write("u_vis,v_vis,u_ir,v_ir\n\n1,2,3,abc\n");
  CHECK_THROWS_WITH(LoadPixelPairs(word), Catch::StartsWith(word + ":3: 'abc' is not a number"));
  const std::string trailing = Write("u_vis,v_vis,u_ir,v_ir\n1,2,3,4px\n");
  CHECK_THROWS_WITH(LoadPixelPairs(trailing), Catch::Contains(":2: '4px' is not a number"));
  const std::string inf = Write("u_vis,v_vis,u_ir,v_ir\n1,2,inf,4\n");
  CHECK_THROWS_WITH(LoadPixelPairs(inf), Catch::Contains(":2: 'inf' is not finite"));
  const std::string empty = Write("");
  CHECK_THROWS_WITH(LoadPixelPairs(empty), Catch::Contains("empty pairs file"));
  CHECK_THROWS_WITH(LoadPixelPairs("/nonexistent/p.csv"),
                    Catch::Contains("/nonexistent/p.csv: cannot open pairs file"));
}

TEST_CASE("Pixel pairs file keeps the depths in a fifth column when there are any") {
  const std::vector<PixelPair> pairs = {{1.25, 2.5, 3.125, 4.0625, 1.5},
                                        {639.7, 479.3, 600.01, 450.99, 0}};
  const std::string path = test::MakeTempDir("pairs_z") + "/p.csv";
  SavePixelPairs(pairs, path);
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  CHECK(header == "u_vis,v_vis,u_ir,v_ir,z_ir_m");
  const auto back = LoadPixelPairs(path);
  REQUIRE(back.size() == 2);
  CHECK(back[0].z_ir_m == 1.5);
  CHECK(back[1].z_ir_m == 0);
  CHECK_THROWS_WITH(LoadPixelPairs(Write("u_vis,v_vis,u_ir,v_ir,z_ir_m\n1,2,3,4\n")),
                    Catch::Contains(":2: expected 5"));
  CHECK_THROWS_WITH(LoadPixelPairs(Write("u_vis,v_vis,u_ir,v_ir,z_ir_m\n1,2,3,4,-1\n")),
                    Catch::Contains("z_ir_m must be >= 0"));
}
