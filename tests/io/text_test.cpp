#include "rgbdvo/io/text.hpp"

#include <catch2/catch.hpp>
#include <fstream>

#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("List files: comments, blank lines and CRs skipped, line numbers kept") {
  const std::string path = test::MakeTempDir("text") + "/list.txt";
  std::ofstream(path) << "# header\r\n\n  \t\r\n1.0 a.png\r\n  # indented comment\n2.0 b.png";
  const std::vector<ListLine> lines = ReadListLines(path, "list file");
  REQUIRE(lines.size() == 2);
  CHECK(lines[0].number == 4);
  CHECK(lines[0].text == "1.0 a.png");
  CHECK(lines[1].number == 6);
  CHECK(lines[1].text == "2.0 b.png");
  CHECK_THROWS_WITH(ReadListLines(path + ".none", "list file"),
                    Catch::Contains("list.txt.none: cannot open list file"));
}
