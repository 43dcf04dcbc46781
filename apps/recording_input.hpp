#pragma once
// What `run` reads: a recorded folder (TUM RGB-D, fakenect), a ROS 1 bag or a ROS 2 bag, with
// its calibration (--calib, or a bag's own camera_info), and the flags that choose them.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame_source.hpp"
#include "rgbdvo/sources/open_source.hpp"

namespace rgbdvo::cli {

struct RecordingArgs {
  std::string path, calib;
  SourceOptions source;
  bool depth_scale_given = false;
  std::string pairing = "nearest";  // --pairing, as ParsePairing takes it
  // ROS bag topics (rosbag_source.hpp's defaults: the TUM bags').
  std::string rgb_topic = "/camera/rgb/image_color", depth_topic = "/camera/depth/image";
  std::string rgb_info_topic = "/camera/rgb/camera_info";
  std::string depth_info_topic = "/camera/depth/camera_info";
  // Which topic flags were given: a ROS 2 bag chooses the others itself (ros2_bag_source.hpp).
  bool rgb_topic_given = false, depth_topic_given = false;
  bool rgb_info_topic_given = false, depth_info_topic_given = false;
  void AddFlags(CLI::App* cmd);  // --calib, --depth-scale, --max-dt, --pairing, the topic flags
};

struct Recording {
  std::unique_ptr<FrameSource> source;
  Calibration calib;
  std::string calib_source;         // the file, or where in the bag the camera came from
  std::vector<std::string> inputs;  // files the run reads (outputs must not overwrite them)
  std::string groundtruth;          // the folder's groundtruth.txt ("" for a bag)
};

// True when `path` is a file that starts as a ROS 1 bag does ("#ROSBAG V2.0").
bool IsRosbagFile(const std::string& path);

// Opens the recording and its calibration. Throws naming the file or the cause: a bag without
// --calib nor camera_info, a bag where ROS bag support was not built.
Recording OpenRecordingInput(const RecordingArgs& args);

}  // namespace rgbdvo::cli
