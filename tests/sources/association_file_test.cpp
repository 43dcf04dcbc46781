// The TUM tools' association files: read as given, and run as the folder they pair.
#include "rgbdvo/sources/association_file.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "rgbdvo/sources/open_source.hpp"
#include "rgbdvo/sources/tum_source.hpp"
#include "rgbdvo/util/temp_dir.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

namespace {

const std::string kExcerpt = SourceDir() + "/data/tum_fr1_xyz_first30";

// The excerpt's pairs as association lines, paths absolute or relative to the folder.
std::string AssociationText(bool absolute) {
  std::string text = "# t_rgb rgb t_depth depth\n";
  const std::string prefix = absolute ? kExcerpt + "/" : "";
  // TumSource's rule written out: the nearest depth image, the later on a tie.
  const std::vector<TumListEntry> rgb = ReadTumList(kExcerpt + "/rgb.txt");
  const std::vector<TumListEntry> depth = ReadTumList(kExcerpt + "/depth.txt");
  for (const TumListEntry& r : rgb) {
    const TumListEntry* best = &depth.front();
    for (const TumListEntry& d : depth)
      if (std::abs(d.timestamp - r.timestamp) <= std::abs(best->timestamp - r.timestamp)) best = &d;
    char line[512];
    std::snprintf(line, sizeof line, "%.6f %s%s %.6f %s%s\n", r.timestamp, prefix.c_str(),
                  r.path.c_str(), best->timestamp, prefix.c_str(), best->path.c_str());
    text += line;
  }
  return text;
}

}  // namespace

TEST_CASE("Association files are read line by line, errors name the file and line") {
  const ScopedTempDir dir("rgbdvo_test_assoc_");
  const std::string path = dir.path() + "/a.txt";
  std::ofstream(path) << "# comment\n1.0 rgb/1.png 1.01 depth/1.png\r\n\n2.0 rgb/2.png 1.99 "
                         "depth/2.png\n";
  REQUIRE(IsAssociationFile(path));
  const std::vector<TumPair> pairs = ReadAssociations(path);
  REQUIRE(pairs.size() == 2);
  CHECK(pairs[1].rgb.timestamp == 2.0);
  CHECK(pairs[1].depth.path == "depth/2.png");

  std::ofstream(path, std::ios::app) << "3.0 rgb/3.png\n";
  CHECK_THROWS_WITH(ReadAssociations(path), Catch::Contains(path + ":5"));
  std::ofstream(dir.path() + "/empty.txt") << "# nothing\n";
  CHECK_FALSE(IsAssociationFile(dir.path() + "/empty.txt"));
  CHECK_THROWS_WITH(ReadAssociations(dir.path() + "/empty.txt"), Catch::Contains("empty"));
  std::ofstream(dir.path() + "/list.txt") << "1.0 rgb/1.png\n";  // an rgb.txt is not one
  CHECK_FALSE(IsAssociationFile(dir.path() + "/list.txt"));
  CHECK_THROWS_WITH(OpenRecording(dir.path() + "/list.txt", SourceOptions()),
                    Catch::Contains("list.txt") && Catch::Contains("association"));
}

TEST_CASE(
    "rgbdvo run on an association file, or a folder with only associations.txt, gives "
    "the folder's trajectory") {
  const ScopedTempDir dir("rgbdvo_test_assoc_run_");
  const std::string& d = dir.path();
  std::ofstream(d + "/assoc.txt") << AssociationText(true);
  // A folder laid out as ORB-SLAM's examples expect: images and associations.txt only.
  fs::create_directory(d + "/only");
  fs::create_directory_symlink(kExcerpt + "/rgb", d + "/only/rgb");
  fs::create_directory_symlink(kExcerpt + "/depth", d + "/only/depth");
  std::ofstream(d + "/only/associations.txt") << AssociationText(false);
  std::string out;
  REQUIRE(RunCommand(RgbdvoExe() + " run " + kExcerpt + " --calib tum_fr1 --quiet --tum " + d +
                         "/folder.txt",
                     &out) == 0);
  REQUIRE(
      RunCommand(RgbdvoExe() + " run " + d + "/assoc.txt --calib tum_fr1 --tum " + d + "/file.txt",
                 &out) == 0);
  CHECK_THAT(out, Catch::Contains("association file"));
  REQUIRE(RunCommand(
              RgbdvoExe() + " run " + d + "/only --calib tum_fr1 --quiet --tum " + d + "/only.txt",
              &out) == 0);
  CHECK(Slurp(d + "/file.txt") == Slurp(d + "/folder.txt"));
  CHECK(Slurp(d + "/only.txt") == Slurp(d + "/folder.txt"));
  CHECK(Lines(d + "/folder.txt").size() == 31);  // a header line and 30 poses
}

TEST_CASE(
    "An association file edited out of time order is taken in time order, one pair per colour "
    "timestamp, and rgbdvo run says so") {
  const ScopedTempDir dir("rgbdvo_test_assoc_order_");
  const std::string& d = dir.path();
  // The excerpt's 30 lines with all but the first three reversed, and the sixth repeated at the
  // end: 26 lines below the line before them, one repeating a timestamp.
  std::vector<std::string> lines;
  std::istringstream text(AssociationText(true));
  for (std::string line; std::getline(text, line);)
    if (line[0] != '#') lines.push_back(line);
  REQUIRE(lines.size() == 30);
  std::reverse(lines.begin() + 3, lines.end());
  lines.push_back(lines[27]);  // the excerpt's sixth line, now 28th
  {
    std::ofstream out(d + "/assoc.txt");
    for (const std::string& line : lines) out << line << "\n";
  }
  TumSource source(d, ReadAssociations(d + "/assoc.txt"), d + "/assoc.txt", TumSourceOptions{});
  CHECK(source.rgb_order().out_of_order == 26);
  REQUIRE(source.rgb_order().repeated.size() == 1);
  CHECK(source.rgb_list() == d + "/assoc.txt");
  std::vector<double> stamps;
  while (auto f = source.Next()) stamps.push_back(f->color_timestamp);
  CHECK(stamps.size() == 30);
  CHECK(std::is_sorted(stamps.begin(), stamps.end()));
  CHECK(std::adjacent_find(stamps.begin(), stamps.end()) == stamps.end());

  std::string out;
  REQUIRE(RunCommand(RgbdvoExe() + " run " + kExcerpt + " --calib tum_fr1 --quiet --tum " + d +
                         "/folder.txt",
                     &out) == 0);
  REQUIRE(RunCommand(RgbdvoExe() + " run " + d + "/assoc.txt --calib tum_fr1 --quiet --tum " + d +
                         "/file.txt",
                     &out) == 0);
  CHECK_THAT(out, Catch::Contains("assoc.txt: 26 lines out of time order; frames taken in time "
                                  "order"));
  CHECK_THAT(out, Catch::Contains("assoc.txt: skipping 1 line that repeats an earlier line's "
                                  "timestamp"));
  CHECK(Slurp(d + "/file.txt") == Slurp(d + "/folder.txt"));
}
