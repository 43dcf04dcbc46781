#include "rgbdvo/sources/tum_source.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "test_support.hpp"

using namespace rgbdvo;
namespace fs = std::filesystem;

namespace {

// A tiny TUM folder: rgb frames at the given times, depth frames at the given times.
std::string MakeFolder(const std::vector<double>& rgb_t, const std::vector<double>& depth_t,
                       cv::Size depth_size = {64, 48}) {
  std::string dir = test::MakeTempDir("tum");
  fs::create_directories(dir + "/rgb");
  fs::create_directories(dir + "/depth");
  std::ofstream rgb(dir + "/rgb.txt"), depth(dir + "/depth.txt");
  rgb << "# color images\r\n\n";
  depth << "# depth maps\n";
  for (size_t i = 0; i < rgb_t.size(); ++i) {
    const std::string name = "rgb/" + std::to_string(i) + ".png";
    cv::imwrite(dir + "/" + name, cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 20, 30)));
    rgb << std::fixed << rgb_t[i] << " " << name << "\r\n";
  }
  for (size_t i = 0; i < depth_t.size(); ++i) {
    const std::string name = "depth/" + std::to_string(i) + ".png";
    cv::imwrite(dir + "/" + name, cv::Mat(depth_size, CV_16UC1, cv::Scalar(5000 + 100 * i)));
    depth << std::fixed << depth_t[i] << " " << name << "\n";
  }
  return dir;
}

}  // namespace

TEST_CASE("TumSource pairs each rgb frame with the nearest depth frame within 0.02 s") {
  const std::string dir = MakeFolder({1.00, 1.10, 1.20, 1.30}, {0.995, 1.09, 1.115, 1.35});
  TumSource source(dir, TumSourceOptions{});
  CHECK(source.size() == 2);  // 1.20 and 1.30 have no depth within 0.02 s
  REQUIRE(source.unpaired().size() == 2);
  CHECK(source.unpaired()[0].timestamp == 1.20);
  auto f0 = source.Next();
  REQUIRE(f0);
  CHECK(f0->color_timestamp == 1.00);
  CHECK(f0->timestamp == 0.995);  // poses carry the depth image's time
  CHECK(f0->depth_m.type() == CV_32FC1);
  CHECK(f0->depth_m.at<float>(0, 0) == Approx(1.0));  // depth 0 (5000 / 5000 per m)
  auto f1 = source.Next();
  REQUIRE(f1);
  CHECK(f1->color_timestamp == 1.10);
  CHECK(f1->timestamp == 1.09);
  CHECK(f1->depth_m.at<float>(0, 0) == Approx(5100.0 / 5000));  // 1.09 is nearer than 1.115
  CHECK_FALSE(source.Next());
}

TEST_CASE("TumSource errors name the missing folder, list file or bad line") {
  CHECK_THROWS_WITH(TumSource("/nonexistent/rgbdvo", TumSourceOptions{}),
                    Catch::Contains("/nonexistent/rgbdvo") && Catch::Contains("no such folder"));
  const std::string dir = MakeFolder({1.0}, {1.0});
  fs::remove(dir + "/depth.txt");
  CHECK_THROWS_WITH(TumSource(dir, TumSourceOptions{}), Catch::Contains("depth.txt"));
  std::ofstream(dir + "/depth.txt") << "# ok\n1.0 depth/0.png\nnot-a-number depth/1.png\n";
  CHECK_THROWS_WITH(TumSource(dir, TumSourceOptions{}), Catch::Contains("depth.txt:3"));
}

TEST_CASE("TumSource rejects an empty sequence") {
  const std::string empty = MakeFolder({}, {});
  CHECK_THROWS_WITH(TumSource(empty, TumSourceOptions{}), Catch::Contains("empty sequence"));
  const std::string far = MakeFolder({1.0, 2.0}, {5.0});
  CHECK_THROWS_WITH(TumSource(far, TumSourceOptions{}), Catch::Contains("empty sequence"));
}

TEST_CASE("TumSource names unreadable, truncated and wrongly sized images") {
  const std::string dir = MakeFolder({1.0, 1.1}, {1.0, 1.1}, {32, 24});
  TumSource wrong_size(dir, TumSourceOptions{});
  CHECK_THROWS_WITH(wrong_size.Next(), Catch::Contains("depth/0.png") && Catch::Contains("32x24"));

  const std::string ok = MakeFolder({1.0, 1.1}, {1.0, 1.1});
  fs::resize_file(ok + "/rgb/1.png", 40);  // truncated PNG
  TumSource truncated(ok, TumSourceOptions{});
  CHECK(truncated.Next());
  CHECK_THROWS_WITH(truncated.Next(), Catch::Contains("rgb/1.png"));

  const std::string gone = MakeFolder({1.0}, {1.0});
  fs::remove(gone + "/depth/0.png");
  TumSource missing(gone, TumSourceOptions{});
  CHECK_THROWS_WITH(missing.Next(), Catch::Contains("depth/0.png"));
}

TEST_CASE("TumSource takes rgb.txt in time order, one frame per timestamp") {
  // A list edited by hand: 1.10 before 1.00, and 1.20 twice (its second image differs).
  const std::string dir = MakeFolder({1.10, 1.00, 1.20, 1.20, 1.30}, {1.00, 1.10, 1.20, 1.30});
  TumSource source(dir, TumSourceOptions{});
  CHECK(source.rgb_order().out_of_order == 1);
  REQUIRE(source.rgb_order().repeated.size() == 1);
  CHECK(source.rgb_order().repeated[0].path == "rgb/3.png");  // the first of the two is kept
  std::vector<double> stamps;
  std::vector<std::string> names;
  while (auto f = source.Next()) {
    stamps.push_back(f->color_timestamp);
    names.push_back(f->name);
  }
  CHECK(stamps == std::vector<double>{1.00, 1.10, 1.20, 1.30});
  CHECK(names == std::vector<std::string>{"rgb/1.png", "rgb/0.png", "rgb/2.png", "rgb/4.png"});

  const std::string in_order = MakeFolder({1.00, 1.10}, {1.00, 1.10});
  TumSource plain(in_order, TumSourceOptions{});
  CHECK(plain.rgb_order().out_of_order == 0);
  CHECK(plain.rgb_order().repeated.empty());
}
