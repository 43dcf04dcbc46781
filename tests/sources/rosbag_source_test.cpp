// ROS 1 bags: written here from the bundled TUM excerpt with ROS's own bag library, then read
// back by RosbagSource and by `rgbdvo run`, against the folder itself; and bad bags.
#include "rgbdvo/sources/rosbag_source.hpp"

#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "rgbdvo/sources/tum_source.hpp"
#include "rgbdvo/util/temp_dir.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

namespace {

const std::string kExcerpt = SourceDir() + "/data/tum_fr1_xyz_first30";

struct BagLayout {
  std::string depth_encoding = "32FC1";  // or 16UC1 (millimetres)
  double depth_time_shift_s = 0;
  bool camera_info = true;
  size_t frames = 30;  // the excerpt's first colour and depth images
  bool half_size_depth = false;
  rosbag::compression::CompressionType compression = rosbag::compression::Uncompressed;
  // Called with each colour message's index before it is written (to spoil one).
  std::function<void(int, sensor_msgs::Image*)> edit_color;
};

sensor_msgs::Image ImageMessage(const cv::Mat& pixels, const std::string& encoding, double t) {
  sensor_msgs::Image m;
  m.header.stamp = ros::Time(t);
  m.height = pixels.rows;
  m.width = pixels.cols;
  m.encoding = encoding;
  m.step = static_cast<uint32_t>(pixels.cols * pixels.elemSize());
  m.data.assign(pixels.datastart, pixels.dataend);
  return m;
}

// The excerpt's images as the TUM bags hold them (rgb8 colour, depth in metres), in time order.
std::string WriteBag(const std::string& path, const BagLayout& layout = {}) {
  const std::vector<TumListEntry> rgb = ReadTumList(kExcerpt + "/rgb.txt");
  const std::vector<TumListEntry> depth = ReadTumList(kExcerpt + "/depth.txt");
  struct Item {
    double t;
    bool color;
    int index;
  };
  std::vector<Item> items;
  for (size_t i = 0; i < std::min(layout.frames, rgb.size()); ++i)
    items.push_back({rgb[i].timestamp, true, int(i)});
  for (size_t i = 0; i < std::min(layout.frames, depth.size()); ++i)
    items.push_back({depth[i].timestamp + layout.depth_time_shift_s, false, int(i)});
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.t < b.t; });
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.setCompression(layout.compression);
  if (layout.camera_info) {
    sensor_msgs::CameraInfo info;
    info.header.stamp = ros::Time(items.front().t);
    info.width = 640, info.height = 480;
    info.distortion_model = "plumb_bob";
    info.D = {0.1, -0.2, 0.001, 0.002, 0.05};
    info.K = {520, 0, 320, 0, 521, 240, 0, 0, 1};
    bag.write("/camera/depth/camera_info", info.header.stamp, info);
  }
  for (const Item& item : items) {
    if (item.color) {
      cv::Mat rgb_pixels;
      cv::cvtColor(cv::imread(kExcerpt + "/" + rgb[item.index].path), rgb_pixels,
                   cv::COLOR_BGR2RGB);
      sensor_msgs::Image m = ImageMessage(rgb_pixels, "rgb8", item.t);
      if (layout.edit_color) layout.edit_color(item.index, &m);
      bag.write("/camera/rgb/image_color", m.header.stamp, m);
    } else {
      const cv::Mat raw = cv::imread(kExcerpt + "/" + depth[item.index].path, cv::IMREAD_UNCHANGED);
      cv::Mat pixels;
      if (layout.depth_encoding == "16UC1")
        raw.convertTo(pixels, CV_16U, 1000.0 / 5000.0);
      else
        raw.convertTo(pixels, CV_32F, 1.0 / 5000.0);  // as the folder reader scales it
      if (layout.half_size_depth) cv::resize(pixels, pixels, {}, 0.5, 0.5, cv::INTER_NEAREST);
      const sensor_msgs::Image m = ImageMessage(pixels, layout.depth_encoding, item.t);
      bag.write("/camera/depth/image", m.header.stamp, m);
    }
  }
  return path;
}

std::string Run(const std::string& args, int* code) {
  std::string out;
  *code = RunCommand(RgbdvoExe() + " " + args, &out);
  return out;
}

}  // namespace

TEST_CASE("A bag of the excerpt gives the folder's frames: same pairs, stamps and pixels") {
  const ScopedTempDir dir("rgbdvo_test_bag_");
  const std::string bag = WriteBag(dir.path() + "/x.bag");
  TumSource folder(kExcerpt, TumSourceOptions());
  RosbagSource source(bag, RosbagSourceOptions());
  int frames = 0;
  while (std::optional<Frame> expected = folder.Next()) {
    const std::optional<Frame> got = source.Next();
    REQUIRE(got);
    CHECK(got->index == expected->index);
    CHECK(got->color_timestamp == Approx(expected->color_timestamp).margin(1e-6));
    CHECK(got->timestamp == Approx(expected->timestamp).margin(1e-6));
    CHECK(cv::norm(got->bgr, expected->bgr, cv::NORM_INF) == 0);
    CHECK(cv::norm(got->depth_m, expected->depth_m, cv::NORM_INF) == 0);
    ++frames;
  }
  CHECK_FALSE(source.Next());
  CHECK(frames == 30);
  CHECK(source.unpaired() == 0);
  const std::optional<Calibration> calib = source.CameraInfoCalibration();
  REQUIRE(calib);
  CHECK(calib->fx == 520);
  CHECK(calib->fy == 521);
  CHECK(calib->dist_ir[4] == 0.05);
  CHECK(calib->A == 1);
  CHECK(calib->D == 0);
}

TEST_CASE("A bag's 16UC1 depth is read as millimetres, from compressed chunks too") {
  BagLayout layout;
  layout.depth_encoding = "16UC1";
  layout.compression = GENERATE(rosbag::compression::Uncompressed, rosbag::compression::BZ2,
                                rosbag::compression::LZ4);
  layout.frames = 2;
  const ScopedTempDir dir("rgbdvo_test_bag16_");
  const std::string bag = WriteBag(dir.path() + "/x.bag", layout);
  TumSource folder(kExcerpt, TumSourceOptions());
  RosbagSource source(bag, RosbagSourceOptions());
  const Frame expected = *folder.Next(), got = *source.Next();
  // Rounded to whole millimetres: within half a millimetre of the folder's depth everywhere.
  CHECK(cv::norm(got.depth_m, expected.depth_m, cv::NORM_INF) <= 0.0005 + 1e-6);
  CHECK(cv::countNonZero(got.depth_m) == cv::countNonZero(expected.depth_m));
}

TEST_CASE("rgbdvo run on a bag writes the folder's trajectory, and info lists its topics") {
  const ScopedTempDir scoped("rgbdvo_test_bag_run_");
  const std::string& dir = scoped.path();
  const std::string bag = WriteBag(dir + "/x.bag");
  int code = 0;
  Run("run " + kExcerpt + " --calib tum_fr1 --quiet --tum " + dir + "/folder.txt", &code);
  REQUIRE(code == 0);
  Run("run " + bag + " --calib tum_fr1 --quiet --tum " + dir + "/bag.txt", &code);
  REQUIRE(code == 0);
  CHECK(Slurp(dir + "/bag.txt") == Slurp(dir + "/folder.txt"));
  CHECK(Lines(dir + "/bag.txt").size() >= 30);

  // Without --calib, the camera comes from the bag's camera_info.
  const std::string out = Run("run " + bag + " --tum " + dir + "/info.txt", &code);
  CHECK(code == 0);
  CHECK_THAT(out, Catch::Contains("/camera/depth/camera_info"));
  CHECK(Lines(dir + "/info.txt").size() == Lines(dir + "/bag.txt").size());

  const std::string info = Run("info " + bag, &code);
  CHECK(code == 0);
  CHECK_THAT(info, Catch::Contains("/camera/rgb/image_color") &&
                       Catch::Contains("sensor_msgs/Image") && Catch::Contains("30"));
}

TEST_CASE("Bad bags: one line naming the file, topic or message, and rows already written kept") {
  const ScopedTempDir scoped("rgbdvo_test_bag_bad_");
  const std::string& dir = scoped.path();
  BagLayout small;
  small.frames = 14;
  const std::string good = WriteBag(dir + "/good.bag", small);
  int code = 0;

  SECTION("truncated") {
    const std::string bytes = Slurp(good);
    std::ofstream(dir + "/cut.bag", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    const std::string out =
        Run("run " + dir + "/cut.bag --calib tum_fr1 --csv " + dir + "/t.csv", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains(dir + "/cut.bag") && Catch::Contains("reindex"));
  }
  SECTION("not a bag") {
    std::ofstream(dir + "/text.bag") << "hello\n";
    const std::string out = Run("run " + dir + "/text.bag --calib tum_fr1", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("text.bag") && Catch::Contains("ROSBAG"));
  }
  SECTION("a missing topic names it and lists the bag's") {
    const std::string out = Run("run " + good + " --calib tum_fr1 --rgb-topic /kinect/rgb", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("/kinect/rgb") && Catch::Contains("/camera/rgb/image_color"));
  }
  SECTION("a topic of another type") {
    const std::string out =
        Run("run " + good + " --calib tum_fr1 --depth-topic /camera/depth/camera_info", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("sensor_msgs/CameraInfo") && Catch::Contains("expected"));
  }
  SECTION("colour and depth never within the window") {
    BagLayout layout = small;
    layout.depth_time_shift_s = 10;
    const std::string bag = WriteBag(dir + "/apart.bag", layout);
    const std::string out = Run("run " + bag + " --calib tum_fr1", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("within"));
  }
  SECTION("depth of another size than colour") {
    BagLayout layout = small;
    layout.half_size_depth = true;
    const std::string bag = WriteBag(dir + "/half.bag", layout);
    const std::string out = Run("run " + bag + " --calib tum_fr1", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("/camera/depth/image") && Catch::Contains("320x240") &&
                        Catch::Contains("640x480"));
  }
  SECTION("no camera_info and no --calib") {
    BagLayout layout = small;
    layout.camera_info = false;
    const std::string bag = WriteBag(dir + "/noinfo.bag", layout);
    const std::string out = Run("run " + bag, &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("--calib"));
  }
  SECTION("an unknown encoding and a short message, after frames already written") {
    for (const std::string spoil : {"encoding", "size"}) {
      BagLayout layout = small;
      layout.edit_color = [&](int index, sensor_msgs::Image* m) {
        if (index < 12) return;
        if (spoil == "encoding")
          m->encoding = "yuv422";
        else
          m->data.resize(m->data.size() / 2);
      };
      const std::string bag = WriteBag(dir + "/" + spoil + ".bag", layout);
      const std::string csv = dir + "/" + spoil + ".csv";
      const std::string out = Run("run " + bag + " --calib tum_fr1 --csv " + csv, &code);
      CHECK(code == 1);
      CHECK_THAT(out, Catch::Contains("/camera/rgb/image_color") &&
                          Catch::Contains(spoil == "encoding" ? "yuv422" : "bytes"));
      // Every frame before the spoilt one (0-11) is in the trajectory, after the header line.
      int rows = 0;
      for (const std::string& line : Lines(csv)) rows += !line.empty() && line[0] != '#';
      CHECK(rows == 13);
    }
  }
}
