#include "rgbdvo/util/input_file.hpp"

#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("ReadTextFile drops a UTF-8 byte order mark at the start, and only there") {
  const std::string dir = test::MakeTempDir("input_file");
  std::ofstream(dir + "/bom.txt") << "\xEF\xBB\xBF# color images\n1.0 a.png \xEF\xBB\xBF\n";
  CHECK(ReadTextFile(dir + "/bom.txt", "list file", kMaxListFileBytes) ==
        "# color images\n1.0 a.png \xEF\xBB\xBF\n");
  std::ofstream(dir + "/plain.txt") << "1.0 a.png\n";
  CHECK(ReadTextFile(dir + "/plain.txt", "list file", kMaxListFileBytes) == "1.0 a.png\n");
  CHECK(WithoutByteOrderMark("\xEF\xBB") == "\xEF\xBB");
}

TEST_CASE("Input files: a directory is named as one, a missing file is not an error until read") {
  const std::string dir = test::MakeTempDir("input_file");
  CHECK_THROWS_WITH(InputFileSize(dir, "image file"),
                    dir + ": is a directory (image file expected)");
  CHECK_THROWS_WITH(ReadTextFile(dir, "list file", kMaxListFileBytes),
                    dir + ": is a directory (list file expected)");
  CHECK(!InputFileSize(dir + "/none.png", "image file"));
  CHECK_THROWS_WITH(ReadTextFile(dir + "/none.txt", "list file", kMaxListFileBytes),
                    dir + "/none.txt: cannot open list file (No such file or directory)");
}

TEST_CASE("Input files: FIFOs and devices are refused before they are opened, text is capped") {
  const std::string dir = test::MakeTempDir("input_file");
  const std::string fifo = dir + "/fifo";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(InputFileSize(fifo, "image file"),
                    fifo + ": a FIFO, not a regular file (image file expected)");
  CHECK_THROWS_WITH(ReadTextFile("/dev/zero", "configuration file", kMaxConfigFileBytes),
                    "/dev/zero: a character device, not a regular file (configuration file "
                    "expected)");
  std::ofstream(dir + "/list.txt") << std::string(100, 'x');
  CHECK(ReadTextFile(dir + "/list.txt", "list file", 100).size() == 100);
  CHECK_THROWS_WITH(ReadTextFile(dir + "/list.txt", "list file", 99),
                    dir + "/list.txt: 100 bytes, above the limit of 99 bytes for list files");
}
