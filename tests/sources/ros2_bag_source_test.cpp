// ROS 2 bags: the bundled TUM excerpt written as MCAP (WriteTumAsRos2Bag), then read back by
// Ros2BagSource and by `rgbdvo run` against the folder itself; bags with compressed images and
// topics to choose; bad bags.
#include "rgbdvo/sources/ros2_bag_source.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <tuple>
#include <vector>

#include "rgbdvo/io/mcap_writer.hpp"
#include "rgbdvo/io/ros2_messages.hpp"
#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/sources/tum_source.hpp"
#include "rgbdvo/sources/tum_to_ros2.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

namespace {

const std::string kExcerpt = SourceDir() + "/data/tum_fr1_xyz_first30";

std::string Run(const std::string& args, int* code) {
  std::string out;
  *code = RunCommand(RgbdvoExe() + " " + args, &out);
  return out;
}

size_t Rows(const std::string& csv) {
  size_t rows = 0;
  for (const std::string& line : Lines(csv)) rows += !line.empty() && line[0] != '#';
  return rows;
}

// A bag of the excerpt's first `frames` frames: colour as PNG CompressedImage on
// /cam/color/image_raw/compressed, depth as compressedDepth 16UC1 on
// /cam/depth/image_raw/compressedDepth, camera_info on /cam/color/camera_info, big-endian CDR
// when asked; `spoil` edits the serialised colour message of a frame.
std::string WriteCompressedBag(
    const std::string& path, size_t frames, bool big_endian,
    const std::function<void(size_t, std::vector<uint8_t>*)>& spoil = {}) {
  McapWriter writer(path);
  const uint16_t color =
      writer.AddChannel("/cam/color/image_raw/compressed", kRos2CompressedImageType);
  const uint16_t depth =
      writer.AddChannel("/cam/depth/image_raw/compressedDepth", kRos2CompressedImageType);
  const uint16_t info = writer.AddChannel("/cam/color/camera_info", kRos2CameraInfoType);
  Ros2CameraInfo camera;
  camera.k = {520, 0, 320, 0, 521, 240, 0, 0, 1};
  camera.distortion_model = "plumb_bob";
  camera.d = {0.1, -0.2, 0.001, 0.002, 0.05};
  writer.Write(info, 1, EncodeRos2CameraInfo(camera, big_endian));
  TumSource folder(kExcerpt, TumSourceOptions());
  for (size_t i = 0; i < frames; ++i) {
    const Frame f = *folder.Next();
    Ros2CompressedImage c, d;
    c.header.sec = static_cast<int32_t>(f.color_timestamp);
    c.header.nanosec =
        static_cast<uint32_t>(std::llround((f.color_timestamp - c.header.sec) * 1e9));
    c.format = "png";
    cv::imencode(".png", f.bgr, c.data);
    d.header.sec = static_cast<int32_t>(f.timestamp);
    d.header.nanosec = static_cast<uint32_t>(std::llround((f.timestamp - d.header.sec) * 1e9));
    d.format = "16UC1; compressedDepth png";
    d.data.assign(12, 0);
    cv::Mat mm;
    f.depth_m.convertTo(mm, CV_16U, 1000.0);
    std::vector<uint8_t> png;
    cv::imencode(".png", mm, png);
    d.data.insert(d.data.end(), png.begin(), png.end());
    std::vector<uint8_t> color_bytes = EncodeRos2CompressedImage(c, big_endian);
    if (spoil) spoil(i, &color_bytes);
    writer.Write(color, 10 + 2 * i, color_bytes);
    writer.Write(depth, 11 + 2 * i, EncodeRos2CompressedImage(d, big_endian));
  }
  writer.Close();
  return path;
}

}  // namespace

TEST_CASE("An MCAP bag of the excerpt gives the folder's frames: same pairs, stamps and pixels") {
  const std::string dir = MakeTempDir("ros2_bag");
  TumToRos2Options options;
  options.compression = GENERATE(std::string("zstd"), std::string("lz4"), std::string(""));
  const std::string bag = dir + "/x" + options.compression + ".mcap";
  CHECK(WriteTumAsRos2Bag(kExcerpt, bag, options) == 30);
  TumSource folder(kExcerpt, TumSourceOptions());
  Ros2BagSource source(bag, Ros2BagSourceOptions());
  CHECK(source.chosen().rgb_topic == "/camera/rgb/image_color");
  CHECK(source.chosen().depth_topic == "/camera/depth/image");
  CHECK(source.chosen().depth_info_topic == "/camera/depth/camera_info");
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
  CHECK(calib->fx == 525);
  CHECK(calib->cx == 319.5);
}

TEST_CASE("An MCAP bag's 16UC1 depth is read as millimetres") {
  const std::string dir = MakeTempDir("ros2_bag16");
  TumToRos2Options options;
  options.depth_encoding = "16UC1";
  options.count = 3;
  const std::string bag = dir + "/x.mcap";
  CHECK(WriteTumAsRos2Bag(kExcerpt, bag, options) == 3);
  TumSource folder(kExcerpt, TumSourceOptions());
  Ros2BagSource source(bag, Ros2BagSourceOptions());
  const Frame expected = *folder.Next(), got = *source.Next();
  // Rounded to whole millimetres: within half a millimetre of the folder's depth everywhere.
  CHECK(cv::norm(got.depth_m, expected.depth_m, cv::NORM_INF) <= 0.0005 + 1e-6);
  CHECK(cv::countNonZero(got.depth_m) == cv::countNonZero(expected.depth_m));
}

TEST_CASE("Compressed colour and compressedDepth topics chosen by name, CDR of either order") {
  const std::string dir = MakeTempDir("ros2_compressed");
  const bool big = GENERATE(false, true);
  const std::string bag = WriteCompressedBag(dir + "/c.mcap", 3, big);
  TumSource folder(kExcerpt, TumSourceOptions());
  Ros2BagSource source(bag, Ros2BagSourceOptions());
  CHECK(source.chosen().rgb_topic == "/cam/color/image_raw/compressed");
  CHECK(source.chosen().depth_topic == "/cam/depth/image_raw/compressedDepth");
  CHECK(source.chosen().rgb_info_topic == "/cam/color/camera_info");
  const Frame expected = *folder.Next(), got = *source.Next();
  CHECK(cv::norm(got.bgr, expected.bgr, cv::NORM_INF) == 0);
  CHECK(cv::norm(got.depth_m, expected.depth_m, cv::NORM_INF) <= 0.0005 + 1e-6);
  const std::optional<Calibration> calib = source.CameraInfoCalibration();
  REQUIRE(calib);
  CHECK(calib->fy == 521);
  CHECK(calib->dist_ir[4] == 0.05);
}

TEST_CASE("rgbdvo run on an MCAP bag writes the folder's trajectory, and info lists its topics") {
  const std::string dir = MakeTempDir("ros2_bag_run");
  const std::string bag = dir + "/x.mcap";
  WriteTumAsRos2Bag(kExcerpt, bag, TumToRos2Options());
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
  CHECK_THAT(info, Catch::Contains("ROS 2 bag") && Catch::Contains("/camera/rgb/image_color") &&
                       Catch::Contains("sensor_msgs/msg/Image") && Catch::Contains("30"));
}

TEST_CASE("Bad ROS 2 bags: one line naming the file and the topic or record, rows kept") {
  const std::string dir = MakeTempDir("ros2_bag_bad");
  TumToRos2Options small;
  small.count = 14;
  const std::string good = dir + "/good.mcap";
  WriteTumAsRos2Bag(kExcerpt, good, small);
  int code = 0;

  SECTION("two colour topics: none chosen, the flag named") {
    McapWriter writer(dir + "/two.mcap");
    writer.AddChannel("/a/image", kRos2ImageType);
    writer.AddChannel("/b/image", kRos2ImageType);
    writer.AddChannel("/depth", kRos2ImageType);
    writer.Close();
    const std::string out = Run("run " + dir + "/two.mcap --calib tum_fr1", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("two.mcap") && Catch::Contains("--rgb-topic") &&
                        Catch::Contains("/a/image") && Catch::Contains("/b/image"));
  }
  SECTION("a topic of another type") {
    const std::string out =
        Run("run " + good + " --calib tum_fr1 --depth-topic /camera/depth/camera_info", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("sensor_msgs/msg/CameraInfo") && Catch::Contains("expected"));
  }
  SECTION("a missing topic names it and lists the bag's") {
    const std::string out = Run("run " + good + " --calib tum_fr1 --rgb-topic /kinect/rgb", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("/kinect/rgb") && Catch::Contains("/camera/rgb/image_color"));
  }
  SECTION("not an MCAP file") {
    std::ofstream(dir + "/text.mcap") << "hello, this is not a bag\n";
    const std::string out = Run("run " + dir + "/text.mcap --calib tum_fr1", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("text.mcap") && Catch::Contains("MCAP"));
  }
  SECTION("cut mid-stream: the record named, rows already written kept") {
    const std::string bytes = Slurp(good);
    std::ofstream(dir + "/cut.mcap", std::ios::binary) << bytes.substr(0, bytes.size() * 3 / 4);
    const std::string out =
        Run("run " + dir + "/cut.mcap --calib tum_fr1 --csv " + dir + "/cut.csv", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("cut.mcap") && Catch::Contains("Chunk record at offset"));
    // The frames before the cut are run and written (the header line, then their rows).
    CHECK(Rows(dir + "/cut.csv") >= 6);
  }
  SECTION("CDR shorter than its lengths, after frames already written") {
    const std::string bag = WriteCompressedBag(dir + "/short.mcap", 14, false,
                                               [](size_t i, std::vector<uint8_t>* bytes) {
                                                 if (i >= 12) bytes->resize(bytes->size() / 2);
                                               });
    const std::string csv = dir + "/short.csv";
    const std::string out = Run("run " + bag + " --calib tum_fr1 --csv " + csv, &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("short.mcap") &&
                        Catch::Contains("/cam/color/image_raw/compressed") &&
                        Catch::Contains("data"));
    // Frames 0-11 paired and run before the spoilt one, after the header line.
    CHECK(Rows(csv) == 13);
  }
  SECTION("an unknown message type on an image topic") {
    McapWriter writer(dir + "/mixed.mcap");
    const uint16_t color = writer.AddChannel("/cam/rgb/image", kRos2ImageType);
    const uint16_t depth = writer.AddChannel("/cam/depth/image", "sensor_msgs/msg/PointCloud2");
    writer.Write(color, 1, EncodeRos2Image(Ros2Image()));
    writer.Write(depth, 2, {0, 1, 0, 0});
    writer.Close();
    const std::string out = Run("run " + dir + "/mixed.mcap --calib tum_fr1", &code);
    CHECK(code == 1);
    CHECK_THAT(out, Catch::Contains("mixed.mcap") && Catch::Contains("/cam/depth/image") &&
                        Catch::Contains("sensor_msgs/msg/PointCloud2"));
  }
}

TEST_CASE("A .db3 bag and a split rosbag2 folder give the folder's trajectory") {
  const std::string dir = MakeTempDir("ros2_db3");
  TumToRos2Options options;
  options.storage = "sqlite3";
  const std::string db3 = dir + "/x.db3";
  CHECK(WriteTumAsRos2Bag(kExcerpt, db3, options) == 30);
  // A folder of three split files, MCAP and sqlite3, named so that name order is not the
  // order metadata.yaml gives.
  fs::create_directories(dir + "/split");
  TumToRos2Options part = options;
  part.count = 10;
  for (const auto& [first, name, storage] :
       std::vector<std::tuple<size_t, std::string, std::string>>{
           {0, "b_9.db3", "sqlite3"}, {10, "b_10.mcap", "mcap"}, {20, "b_2.db3", "sqlite3"}}) {
    part.first = first;
    part.storage = storage;
    CHECK(WriteTumAsRos2Bag(kExcerpt, dir + "/split/" + name, part) == 10);
  }
  std::ofstream(dir + "/split/metadata.yaml")
      << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
         "  relative_file_paths:\n    - b_9.db3\n    - b_10.mcap\n    - \"b_2.db3\"\n"
         "  duration:\n    nanoseconds: 1\n";
  int code = 0;
  Run("run " + kExcerpt + " --calib tum_fr1 --quiet --tum " + dir + "/folder.txt", &code);
  REQUIRE(code == 0);
  for (const std::string& bag : {db3, dir + "/split"}) {
    INFO(bag);
    Run("run " + bag + " --calib tum_fr1 --quiet --tum " + dir + "/bag.txt", &code);
    CHECK(code == 0);
    CHECK(Slurp(dir + "/bag.txt") == Slurp(dir + "/folder.txt"));
    const std::string info = Run("info " + bag, &code);
    CHECK(code == 0);
    CHECK_THAT(info, Catch::Contains("/camera/depth/image") && Catch::Contains("30"));
  }
}

TEST_CASE("Bad .db3 bags and folders: one line naming the file, exit 1") {
  const std::string dir = MakeTempDir("ros2_db3_bad");
  int code = 0;
  std::ofstream(dir + "/text.db3") << "this is no database, only text long enough to look\n";
  std::string out = Run("run " + dir + "/text.db3 --calib tum_fr1", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("text.db3") && Catch::Contains("sqlite3"));

  fs::create_directories(dir + "/nolist");
  std::ofstream(dir + "/nolist/metadata.yaml") << "rosbag2_bagfile_information:\n  version: 5\n";
  out = Run("run " + dir + "/nolist --calib tum_fr1", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("metadata.yaml") && Catch::Contains("relative_file_paths"));

  fs::create_directories(dir + "/zstd");
  std::ofstream(dir + "/zstd/metadata.yaml")
      << "rosbag2_bagfile_information:\n  relative_file_paths:\n  - x_0.mcap.zstd\n";
  out = Run("run " + dir + "/zstd --calib tum_fr1", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::Contains("x_0.mcap.zstd"));
}

TEST_CASE("16UC1 bags (MCAP lz4 and .db3) give the folder's trajectory within a millimetre") {
  const std::string dir = MakeTempDir("ros2_bag16_run");
  int code = 0;
  Run("run " + kExcerpt + " --calib tum_fr1 --quiet --tum " + dir + "/folder.txt", &code);
  REQUIRE(code == 0);
  const Trajectory folder = ReadTrajectory(dir + "/folder.txt");
  TumToRos2Options options;
  options.depth_encoding = "16UC1";
  options.compression = "lz4";
  for (const std::string storage : {"mcap", "sqlite3"}) {
    options.storage = storage;
    const std::string bag = dir + "/x16." + (storage == "mcap" ? "mcap" : "db3");
    WriteTumAsRos2Bag(kExcerpt, bag, options);
    Run("run " + bag + " --calib tum_fr1 --quiet --tum " + dir + "/bag.txt", &code);
    REQUIRE(code == 0);
    const Trajectory got = ReadTrajectory(dir + "/bag.txt");
    REQUIRE(got.poses.size() == folder.poses.size());
    // Depth rounded to whole millimetres moves each pose by far less than a millimetre.
    double worst_m = 0;
    for (size_t i = 0; i < got.poses.size(); ++i) {
      CHECK(got.poses[i].timestamp == folder.poses[i].timestamp);
      worst_m = std::max(worst_m, (got.poses[i].world_from_cam.translation() -
                                   folder.poses[i].world_from_cam.translation())
                                      .norm());
    }
    INFO(storage << ": largest position difference " << worst_m << " m");
    CHECK(worst_m < 0.001);
  }
}
