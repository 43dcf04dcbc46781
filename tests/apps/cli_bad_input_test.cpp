// End-to-end tests of hostile input files: what reaches the terminal from them.
#include <catch2/catch.hpp>
#include <fstream>
#include <string>

#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

std::string Rgbdvo(const std::string& args, int* code) {
  std::string out;
  *code = RunCommand(RgbdvoExe() + " " + args, &out);
  return out;
}

// The calibration of the synthetic folder's camera.
std::string Calib(const std::string& dir) {
  const std::string path = dir + "/calib.yaml";
  std::ofstream(path) << "A: 1.\nB: 0.\nC: 1.\nD: 0.\n"
                         "K_ir: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
                         "   data: [ 525., 0., 319.5, 0., 525., 239.5, 0., 0., 1. ]\n"
                         "min_depth_m: 0.4\nmax_depth_m: 8.\n";
  return path;
}

bool HasTerminalControl(const std::string& s) {
  return s.find('\x1b') != std::string::npos || s.find('\x9b') != std::string::npos ||
         s.find('\x07') != std::string::npos;
}

}  // namespace

TEST_CASE("Control bytes quoted from input files reach the terminal escaped") {
  const std::string dir = MakeTempDir("cli_escape");
  WriteTumSequence(dir, SyntheticScene(), PinholeCamera(), MakeSmoothPath(2));
  int code = 0;

  // rgb.txt: a line that clears the screen and retitles the window.
  std::ofstream(dir + "/rgb.txt") << "\x1b[2J\x1b]0;owned\x07 rgb/1.png\n";
  std::string out = Rgbdvo("run " + dir + " --calib " + Calib(dir), &code);
  INFO(out);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("rgb.txt:1:") && Catch::Contains("\\x1b[2J\\x1b]0;owned\\x07"));
  CHECK(!HasTerminalControl(out));

  // An image path in rgb.txt (quoted as the file that cannot be read).
  std::ofstream(dir + "/rgb.txt") << "0 rgb/\x1b[31mred.png\n";
  std::ofstream(dir + "/depth.txt") << "0 depth/\x9b"
                                       "31mred.png\n";
  out = Rgbdvo("run " + dir + " --calib " + Calib(dir), &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("rgb/\\x1b[31mred.png"));
  CHECK(!HasTerminalControl(out));

  // A calibration key (8-bit CSI: not a control byte in ASCII).
  std::ofstream(dir + "/bad.yaml") << "\x9b[2J: 1\n";
  out = Rgbdvo("run " + dir + " --calib " + dir + "/bad.yaml", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("bad key '\\x9b[2J'"));
  CHECK(!HasTerminalControl(out));

  // A trajectory row.
  std::ofstream(dir + "/t.txt") << "1 0 0 \x1b[31mx 0 0 0 1\n";
  out = Rgbdvo("eval " + dir + "/t.txt " + dir + "/t.txt", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("t.txt:1: tz: '\\x1b[31mx' is not a number"));
  CHECK(!HasTerminalControl(out));
}
