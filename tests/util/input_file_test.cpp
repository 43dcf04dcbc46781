#include "rgbdvo/util/input_file.hpp"

#include <catch2/catch.hpp>
#include <fstream>

#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("ReadTextFile drops a UTF-8 byte order mark at the start, and only there") {
  const std::string dir = test::MakeTempDir("input_file");
  std::ofstream(dir + "/bom.txt") << "\xEF\xBB\xBF# color images\n1.0 a.png \xEF\xBB\xBF\n";
  CHECK(ReadTextFile(dir + "/bom.txt", "list file") == "# color images\n1.0 a.png \xEF\xBB\xBF\n");
  std::ofstream(dir + "/plain.txt") << "1.0 a.png\n";
  CHECK(ReadTextFile(dir + "/plain.txt", "list file") == "1.0 a.png\n");
  CHECK(WithoutByteOrderMark("\xEF\xBB") == "\xEF\xBB");
}

TEST_CASE("Input files: a directory is named as one, a missing file is not an error until read") {
  const std::string dir = test::MakeTempDir("input_file");
  CHECK_THROWS_WITH(InputFileSize(dir, "image file"),
                    dir + ": is a directory (image file expected)");
  CHECK_THROWS_WITH(ReadTextFile(dir, "list file"), dir + ": is a directory (list file expected)");
  CHECK(!InputFileSize(dir + "/none.png", "image file"));
  CHECK_THROWS_WITH(ReadTextFile(dir + "/none.txt", "list file"),
                    dir + "/none.txt: cannot open list file (No such file or directory)");
}
