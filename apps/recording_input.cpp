#include "recording_input.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "rgbdvo/sensor/calibration_catalog.hpp"
#include "rgbdvo/sources/association_file.hpp"
#include "rgbdvo/sources/pairing.hpp"
#include "rgbdvo/sources/ros2_bag_source.hpp"
#include "rgbdvo/util/display_text.hpp"
#include "rgbdvo/util/input_file.hpp"
#include "run_common.hpp"
#ifdef RGBDVO_WITH_ROSBAG
#include "rgbdvo/sources/rosbag_source.hpp"
#endif

namespace rgbdvo::cli {

void RecordingArgs::AddFlags(CLI::App* cmd) {
  AddCalibFlag(cmd, &calib,
               "calibration YAML (required for folders; a bag's camera_info when not given)");
  cmd->add_option("--depth-scale", source.tum.depth_units_per_m,
                  "TUM depth units per metre (default: the calibration's depth_units_per_m, else "
                  "5000; bags: from the encoding)")
      ->capture_default_str()
      ->each([this](const std::string&) { depth_scale_given = true; });
  cmd->add_option("--max-dt", source.tum.max_time_diff_s, "max rgb-depth time difference, s")
      ->capture_default_str();
  AddPairingFlag(cmd, &pairing);
  const auto given = [](bool* flag) { return [flag](const std::string&) { *flag = true; }; };
  cmd->add_option("--rgb-topic", rgb_topic,
                  "ROS bag: colour sensor_msgs/Image topic (ROS 2: Image or CompressedImage; "
                  "default: the only image topic without 'depth' in its name)")
      ->capture_default_str()
      ->each(given(&rgb_topic_given));
  cmd->add_option("--depth-topic", depth_topic,
                  "ROS bag: depth sensor_msgs/Image topic (16UC1 mm or 32FC1 m; ROS 2: also "
                  "compressedDepth; default: the only image topic with 'depth' in its name)")
      ->capture_default_str()
      ->each(given(&depth_topic_given));
  cmd->add_option("--rgb-info-topic", rgb_info_topic,
                  "ROS bag: colour sensor_msgs/CameraInfo (ROS 2 default: the camera_info "
                  "beside the colour topic)")
      ->capture_default_str()
      ->each(given(&rgb_info_topic_given));
  cmd->add_option("--depth-info-topic", depth_info_topic,
                  "ROS bag: depth sensor_msgs/CameraInfo (used first; ROS 2 default: the "
                  "camera_info beside the depth topic)")
      ->capture_default_str()
      ->each(given(&depth_info_topic_given));
}

bool IsRosbagFile(const std::string& path) {
  // Checked before the file is opened: a FIFO would block the open.
  if (std::filesystem::is_directory(path) || !InputFileSize(path, "recording file")) return false;
  std::ifstream in(path, std::ios::binary);
  char magic[13] = {};
  return in.read(magic, sizeof magic) && std::string(magic, sizeof magic) == "#ROSBAG V2.0\n";
}

namespace {

// One line on stderr for each change putting the colour list (rgb.txt or an association file)
// in time order made (TimeOrderRepair).
void ReportTimeOrder(const TumSource& tum) {
  const TimeOrderRepair& order = tum.rgb_order();
  const auto lines = [](size_t n) { return std::to_string(n) + (n == 1 ? " line" : " lines"); };
  if (order.out_of_order > 0)
    std::cerr << "rgbdvo: warning: " << Printable(tum.rgb_list()) << ": "
              << lines(order.out_of_order) << " out of time order; frames taken in time order\n";
  if (!order.repeated.empty())
    std::cerr << "rgbdvo: warning: " << Printable(tum.rgb_list()) << ": skipping "
              << lines(order.repeated.size())
              << (order.repeated.size() == 1 ? " that repeats" : " that repeat")
              << " an earlier line's timestamp (first: " << Printable(order.repeated.front().path)
              << ")\n";
}

// The lines of ReportTimeOrder, and one when colour frames found no depth frame (of their own,
// one to one).
void ReportSkippedFrames(const FrameSource& recording, const SourceOptions& options) {
  const bool one_to_one = options.tum.pairing == Pairing::kOneToOne;
  size_t unpaired = 0;
  double window = options.tum.max_time_diff_s;
  std::string first;
  if (auto* tum = dynamic_cast<const TumSource*>(&recording)) {
    ReportTimeOrder(*tum);
    unpaired = tum->unpaired().size();
    if (unpaired > 0) first = " (first: " + Printable(tum->unpaired().front().path) + ")";
  } else if (auto* fakenect = dynamic_cast<const FakenectSource*>(&recording)) {
    unpaired = static_cast<size_t>(fakenect->unpaired());
    window = options.fakenect.max_time_diff_s;
  }
  if (unpaired == 0) return;
  std::cerr << "rgbdvo: skipping " << unpaired << " rgb frames without a depth frame "
            << (one_to_one ? "of their own " : "") << "within " << window << " s"
            << (one_to_one ? ", one-to-one pairing" : "") << first << "\n";
}

// The calibration of a bag's run: --calib, else the bag's camera_info.
void BagCalibration(const RecordingArgs& args, const std::optional<Calibration>& info,
                    const std::string& info_topics, Recording* r) {
  if (!args.calib.empty()) {
    r->calib_source = FindCalibration(args.calib);
    r->calib = LoadCalibration(r->calib_source);
    r->inputs.push_back(r->calib_source);
  } else if (info) {
    r->calib = *info;
    r->calib_source = info->description + " (registered depth: identity colour->depth mapping)";
  } else {
    throw std::runtime_error(args.path + ": no camera_info on " + info_topics +
                             "; give the camera with --calib");
  }
}

Recording OpenRos2Bag(const RecordingArgs& args) {
  if (ParsePairing(args.pairing) != Pairing::kNearest)
    throw std::runtime_error(args.path + ": --pairing " + args.pairing +
                             " is not implemented for ROS bags (they pair nearest in time)");
  Ros2BagSourceOptions options;
  if (args.rgb_topic_given) options.rgb_topic = args.rgb_topic;
  if (args.depth_topic_given) options.depth_topic = args.depth_topic;
  if (args.rgb_info_topic_given) options.rgb_info_topic = args.rgb_info_topic;
  if (args.depth_info_topic_given) options.depth_info_topic = args.depth_info_topic;
  options.max_time_diff_s = args.source.tum.max_time_diff_s;
  auto bag = std::make_unique<Ros2BagSource>(args.path, options);
  if (!bag->scan_error().empty())
    std::cerr << "rgbdvo: warning: " << Printable(bag->scan_error())
              << "; the frames before it are run\n";
  Recording r;
  r.inputs = {args.path};
  const Ros2BagSourceOptions& chosen = bag->chosen();
  const auto named = [](const std::string& topic) { return topic.empty() ? "(none)" : topic; };
  BagCalibration(args, bag->CameraInfoCalibration(),
                 named(chosen.depth_info_topic) + " or " + named(chosen.rgb_info_topic), &r);
  r.source = std::move(bag);
  return r;
}

Recording OpenBag(const RecordingArgs& args) {
#ifdef RGBDVO_WITH_ROSBAG
  if (ParsePairing(args.pairing) != Pairing::kNearest)
    throw std::runtime_error(args.path + ": --pairing " + args.pairing +
                             " is not implemented for ROS bags (they pair nearest in time)");
  RosbagSourceOptions options;
  options.rgb_topic = args.rgb_topic;
  options.depth_topic = args.depth_topic;
  options.rgb_info_topic = args.rgb_info_topic;
  options.depth_info_topic = args.depth_info_topic;
  options.max_time_diff_s = args.source.tum.max_time_diff_s;
  auto bag = std::make_unique<RosbagSource>(args.path, options);
  Recording r;
  r.inputs = {args.path};
  BagCalibration(args, bag->CameraInfoCalibration(),
                 args.depth_info_topic + " or " + args.rgb_info_topic, &r);
  r.source = std::move(bag);
  return r;
#else
  throw std::runtime_error(args.path +
                           ": a ROS bag, but this rgbdvo was built without ROS bag support "
                           "(install librosbag-storage-dev and libsensor-msgs-dev, rebuild)");
#endif
}

}  // namespace

Recording OpenRecordingInput(const RecordingArgs& args) {
  if (!std::filesystem::exists(args.path))
    throw std::runtime_error(args.path + ": no such folder or file");
  if (IsRosbagFile(args.path)) {
    if (args.source.tum.accelerometer)
      throw std::runtime_error(args.path +
                               ": accelerometer readings are not read from ROS bags yet (their "
                               "/imu topic); --gravity and --floor accelerometer need a TUM "
                               "folder with accelerometer.txt or a fakenect recording");
    return OpenBag(args);
  }
  if (IsRos2Bag(args.path)) {
    if (args.source.tum.accelerometer)
      throw std::runtime_error(args.path +
                               ": accelerometer readings are not read from ROS 2 bags yet (their "
                               "sensor_msgs/msg/Imu topic); --gravity and --floor accelerometer "
                               "need a TUM folder with accelerometer.txt or a fakenect recording");
    return OpenRos2Bag(args);
  }
  const bool is_file = !std::filesystem::is_directory(args.path);
  if (is_file && !IsAssociationFile(args.path))
    throw std::runtime_error(args.path +
                             ": neither a recording folder, a ROS 1 bag (no '#ROSBAG V2.0' "
                             "header) nor an association file ('t_rgb rgb_path t_depth "
                             "depth_path' lines)");
  if (args.calib.empty()) throw CLI::RequiredError("--calib");
  Recording r;
  r.calib_source = FindCalibration(args.calib);
  r.calib = LoadCalibration(r.calib_source);
  // The depth scale: --depth-scale, else the calibration's, else TUM's 5000.
  SourceOptions source_options = args.source;
  if (!args.depth_scale_given && r.calib.depth_units_per_m > 0)
    source_options.tum.depth_units_per_m = r.calib.depth_units_per_m;
  source_options.tum.pairing = source_options.fakenect.pairing = ParsePairing(args.pairing);
  r.source = OpenRecording(args.path, source_options);
  ReportSkippedFrames(*r.source, source_options);
  r.inputs = {r.calib_source, args.path};
  const std::filesystem::path folder =
      is_file ? std::filesystem::path(args.path).parent_path() : std::filesystem::path(args.path);
  for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt", "accelerometer.txt",
                           "INDEX.txt", "associations.txt"})
    r.inputs.push_back((folder / name).string());
  r.groundtruth = (folder / "groundtruth.txt").string();
  return r;
}

}  // namespace rgbdvo::cli
