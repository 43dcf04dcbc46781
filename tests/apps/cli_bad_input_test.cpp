// End-to-end tests of hostile input files: what reaches the terminal from them.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "rgbdvo/sources/tum_source.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// Killed when it hangs: open() on a FIFO without a writer never returns, and SIGTERM waits for it.
std::string Rgbdvo(const std::string& args, int* code) {
  std::string out;
  *code = RunCommand("timeout -s KILL 60 " + RgbdvoExe() + " " + args, &out);
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

TEST_CASE("Unclear messages made clear: tiny images, folders as images, long lines") {
  const std::string dir = MakeTempDir("cli_unclear");
  WriteTumSequence(dir, SyntheticScene(), PinholeCamera(), MakeSmoothPath(2));
  const std::string calib = Calib(dir);
  const std::string rgb = dir + "/rgb.txt", depth = dir + "/depth.txt";
  const std::vector<TumListEntry> frames = ReadTumList(rgb);
  const std::vector<TumListEntry> depths = ReadTumList(depth);
  REQUIRE(frames.size() == 2);
  int code = 0;

  // Images 1 pixel wide, colour and depth alike: refused naming the file, not by OpenCV's resize.
  const std::string first_rgb = dir + "/" + frames[0].path;
  const std::string first_depth = dir + "/" + depths[0].path;
  cv::imwrite(first_rgb, cv::Mat(480, 1, CV_8UC3, cv::Scalar(0, 0, 0)));
  cv::imwrite(first_depth, cv::Mat(480, 1, CV_16UC1, cv::Scalar(5000)));
  std::string out = Rgbdvo("run " + dir + " --calib " + calib, &code);
  INFO(out);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains(frames[0].path) && Catch::Contains("1x480") &&
                      Catch::Contains("too small"));
  CHECK_THAT(out, !Catch::Contains("Assertion"));

  // Images of another size than the first frame's.
  cv::imwrite(first_rgb, cv::Mat(48, 64, CV_8UC3, cv::Scalar(0, 0, 0)));
  cv::imwrite(first_depth, cv::Mat(48, 64, CV_16UC1, cv::Scalar(5000)));
  out = Rgbdvo("run " + dir + " --calib " + calib, &code);
  CHECK(code == 1);
  CHECK_THAT(out,
             Catch::Contains(frames[1].path + ": image 640x480, but the first frame's is 64x48"));

  // A folder where an image should be.
  std::filesystem::remove(first_rgb);
  std::filesystem::create_directory(first_rgb);
  out = Rgbdvo("run " + dir + " --calib " + calib, &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains(frames[0].path + ": is a directory"));
  CHECK_THAT(out, !Catch::Contains("9223372036854775807"));

  // An association file with a line of 50 MB: a short quote of it.
  const std::string assoc = dir + "/assoc.txt";
  std::ofstream(assoc) << frames[1].timestamp << " " << frames[1].path << " " << depths[1].timestamp
                       << " " << depths[1].path << "\n1.0 " << std::string(50 << 20, 'x') << "\n";
  out = Rgbdvo("run " + assoc + " --calib " + calib, &code);
  CHECK(code == 1);
  CHECK(out.size() < 400);
  const std::string head = out.substr(0, 400);  // a failure must not print 50 MB
  CHECK_THAT(head, Catch::Contains("assoc.txt:2:") && Catch::Contains("got '1.0 xxx") &&
                       Catch::Contains("xxx...'"));
}

TEST_CASE("A UTF-8 byte order mark at the start of a text input is skipped") {
  const std::string dir = MakeTempDir("cli_bom");
  WriteTumSequence(dir, SyntheticScene(), PinholeCamera(), MakeSmoothPath(3));
  const std::string bom = "\xEF\xBB\xBF";
  const std::string rgb_list = Slurp(dir + "/rgb.txt"), depth_list = Slurp(dir + "/depth.txt");
  REQUIRE(rgb_list.rfind('#', 0) == 0);  // starts with a comment line
  std::ofstream(dir + "/rgb.txt") << bom << rgb_list;
  std::ofstream(dir + "/depth.txt") << bom << depth_list;
  std::ofstream(dir + "/calib_bom.yaml") << bom << Slurp(Calib(dir));
  int code = 0;
  std::string out = Rgbdvo(
      "run " + dir + " --calib " + dir + "/calib_bom.yaml --quiet --tum " + dir + "/t.txt", &code);
  INFO(out);
  CHECK(code == 0);
  // An association file and the trajectories eval reads.
  const std::vector<TumListEntry> frames = ReadTumList(dir + "/rgb.txt");
  const std::vector<TumListEntry> depths = ReadTumList(dir + "/depth.txt");
  {
    std::ofstream assoc(dir + "/assoc.txt");
    assoc << bom;
    for (size_t k = 0; k < frames.size(); ++k)
      assoc << frames[k].timestamp << " " << frames[k].path << " " << depths[k].timestamp << " "
            << depths[k].path << "\n";
  }
  out = Rgbdvo("run " + dir + "/assoc.txt --calib " + dir + "/calib_bom.yaml --quiet", &code);
  CHECK(code == 0);
  std::ofstream(dir + "/t_bom.txt") << bom << Slurp(dir + "/t.txt");
  std::ofstream(dir + "/gt_bom.txt") << bom << Slurp(dir + "/groundtruth.txt");
  out = Rgbdvo("eval " + dir + "/gt_bom.txt " + dir + "/t_bom.txt", &code);
  CHECK(code == 0);
  CHECK_THAT(out, Catch::Contains("ATE (m)"));
}

TEST_CASE("Files that are not regular files are refused before they are opened, text is capped") {
  const std::string dir = MakeTempDir("cli_fifo");
  WriteTumSequence(dir, SyntheticScene(), PinholeCamera(), MakeSmoothPath(2));
  const std::string calib = Calib(dir), fifo = dir + "/fifo";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  int code = 0;
  for (const std::string& args :
       {"run " + fifo + " --calib " + calib,
        "run " + dir + " --calib " + calib + " --config " + fifo, "run " + dir + " --calib " + fifo,
        "eval " + fifo + " " + fifo, "info " + fifo}) {
    const std::string out = Rgbdvo(args, &code);
    INFO(args << "\n" << out);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains(fifo + ": a FIFO, not a regular file"));
  }
  // An image.
  const std::vector<TumListEntry> frames = ReadTumList(dir + "/rgb.txt");
  std::filesystem::remove(dir + "/" + frames[1].path);
  REQUIRE(mkfifo((dir + "/" + frames[1].path).c_str(), 0600) == 0);
  std::string out = Rgbdvo("run " + dir + " --calib " + calib, &code);
  INFO(out);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains(frames[1].path + ": a FIFO, not a regular file (image file"));

  // /dev/zero as configuration: refused, not read without end; a large regular file: capped.
  out = Rgbdvo("run --dump-config --config /dev/zero", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("/dev/zero: a character device, not a regular file"));
  std::ofstream(dir + "/big.cfg") << std::string(2 << 20, '#');
  out = Rgbdvo("run --dump-config --config " + dir + "/big.cfg", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("big.cfg: 2097152 bytes, above the limit of 1 MiB for "
                                  "configuration files"));
}

TEST_CASE(
    "Number flags and configuration values beyond a real camera's range are refused at once") {
  // Each of these once ran for seconds to minutes and took gigabytes before failing or finishing.
  const std::string dir = MakeTempDir("cli_ranges");
  WriteTumSequence(dir, SyntheticScene(), PinholeCamera(), MakeSmoothPath(2));
  const std::string run = "run " + dir + " --calib " + Calib(dir) + " --tum " + dir + "/t.txt ";
  for (const auto& [flag, range] :
       {std::pair<std::string, std::string>{"--threads 1000000", "[0, 256]"},
        {"--track-window 20001", "[3, 101]"},
        {"--track-warp-window 20001", "[3, 101]"},
        {"--octave-layers 5000", "[1, 10]"},
        {"--track-levels 2000000000", "[0, 8]"},
        {"--queue-frames 100000", "[1, 256]"}}) {
    INFO(flag);
    int code = 0;
    const std::string out = Rgbdvo(run + flag, &code);
    INFO(out);
    CHECK(code == 2);
    CHECK_THAT(out, Catch::Contains(flag.substr(0, flag.find(' '))) && Catch::Contains(range));
    CHECK_FALSE(std::filesystem::exists(dir + "/t.txt"));
  }
  const std::string config = dir + "/big.conf";
  std::ofstream(config) << "tracking.window_px = 100001\n";
  int code = 0;
  const std::string out = Rgbdvo(run + "--config " + config, &code);
  INFO(out);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains(config + ":1") && Catch::Contains("[3, 101]"));
}

TEST_CASE(
    "No output overwrites an input: images, lists, calibration, configuration, trajectories") {
  // By device and inode: a hard link to an image is the image.
  const std::string dir = MakeTempDir("cli_onto_inputs");
  WriteTumSequence(dir, SyntheticScene(), PinholeCamera(), MakeSmoothPath(3));
  const std::string calib = Calib(dir);
  const std::vector<TumListEntry> frames = ReadTumList(dir + "/rgb.txt");
  const std::string image = dir + "/" + frames[1].path, link = dir + "/link.png";
  std::filesystem::create_hard_link(image, link);
  const std::string config = dir + "/my.conf";
  std::ofstream(config) << "matching.ratio = 0.8\n";
  const std::string run = "run " + dir + " --calib " + calib + " --config " + config + " ";
  const std::string est = dir + "/est.txt", gt = dir + "/groundtruth.txt";
  int code = 0;
  REQUIRE(Rgbdvo(run + "--tum " + est, &code).size() > 0);
  REQUIRE(code == 0);
  const std::vector<std::string> inputs = {image, dir + "/rgb.txt", calib, config, est, gt};
  std::vector<std::string> before;
  before.reserve(inputs.size());
  for (const std::string& f : inputs) before.push_back(Slurp(f));
  const std::string tum_out = dir + "/fresh.txt";
  const std::pair<std::string, std::string> cases[] = {
      {run + "--tum " + image, "is an input of this command"},
      {run + "--csv " + link, "is an input of this command"},
      {run + "--kitti " + config, "is an input of this command"},
      {run + "--tum " + tum_out + " --plot " + dir + "/rgb.txt", "is an input of this command"},
      {run + "--tum " + tum_out + " --plot " + calib, "is an input of this command"},
      {run + "--tum " + tum_out + " --plot " + tum_out, "given for both --tum and --plot"},
      {"plot " + est + " --png " + est, "is an input of this command"},
      {"plot " + est + " --gt " + gt + " --png " + gt, "is an input of this command"},
      {"eval " + gt + " " + est + " --plot " + est, "is an input of this command"},
      {"eval " + gt + " " + est + " --plot-errors " + gt, "is an input of this command"},
      {"eval " + gt + " " + est + " --plot-xyz " + est, "is an input of this command"},
  };
  for (const auto& [args, expected] : cases) {
    INFO(args);
    const std::string out = Rgbdvo(args, &code);
    INFO(out);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains(expected));
  }
  for (size_t i = 0; i < inputs.size(); ++i) {
    INFO(inputs[i]);
    CHECK(Slurp(inputs[i]) == before[i]);
  }
  CHECK_FALSE(std::filesystem::exists(tum_out));
}
