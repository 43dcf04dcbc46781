// Writes a TUM RGB-D folder as a ROS 1 bag laid out as the TUM bags are (rgb8 colour on
// /camera/rgb/image_color, 32FC1 metres on /camera/depth/image, camera_info beside each), for
// measuring `rgbdvo run` on bags. --repeat N plays the folder N times in a row (stamps moved on)
// to make a long bag from a short folder.
//   rgbdvo_tum_to_bag FOLDER OUT.bag [--repeat N] [--fx F --fy F --cx C --cy C]
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "rgbdvo/sources/tum_source.hpp"

int main(int argc, char** argv) {
  CLI::App app("TUM RGB-D folder -> ROS 1 bag");
  std::string folder, out;
  int repeat = 1;
  double fx = 525, fy = 525, cx = 319.5, cy = 239.5;  // the TUM bags' camera_info
  app.add_option("folder", folder)->required();
  app.add_option("out", out)->required();
  app.add_option("--repeat", repeat)->check(CLI::PositiveNumber);
  app.add_option("--fx", fx);
  app.add_option("--fy", fy);
  app.add_option("--cx", cx);
  app.add_option("--cy", cy);
  CLI11_PARSE(app, argc, argv);
  try {
    rosbag::Bag bag(out, rosbag::bagmode::Write);
    sensor_msgs::CameraInfo info;
    info.width = 640, info.height = 480, info.distortion_model = "plumb_bob";
    info.D = {0, 0, 0, 0, 0};
    info.K = {fx, 0, cx, 0, fy, cy, 0, 0, 1};
    double shift = 0;
    int frames = 0;
    for (int r = 0; r < repeat; ++r) {
      rgbdvo::TumSource source(folder, rgbdvo::TumSourceOptions());
      double last = 0, first = -1;
      while (std::optional<rgbdvo::Frame> f = source.Next()) {
        if (first < 0) first = std::min(f->color_timestamp, f->timestamp);
        const auto message = [](const cv::Mat& m, const std::string& encoding, double t) {
          sensor_msgs::Image image;
          image.header.stamp = ros::Time(t);
          image.height = m.rows, image.width = m.cols, image.encoding = encoding;
          image.step = static_cast<uint32_t>(m.cols * m.elemSize());
          image.data.assign(m.datastart, m.dataend);
          return image;
        };
        cv::Mat rgb;
        cv::cvtColor(f->bgr, rgb, cv::COLOR_BGR2RGB);
        const sensor_msgs::Image color = message(rgb, "rgb8", f->color_timestamp + shift);
        const sensor_msgs::Image depth = message(f->depth_m, "32FC1", f->timestamp + shift);
        info.header.stamp = color.header.stamp;
        const bool color_first = color.header.stamp <= depth.header.stamp;
        bag.write("/camera/rgb/camera_info", info.header.stamp, info);
        bag.write(color_first ? "/camera/rgb/image_color" : "/camera/depth/image",
                  color_first ? color.header.stamp : depth.header.stamp,
                  color_first ? color : depth);
        bag.write(color_first ? "/camera/depth/image" : "/camera/rgb/image_color",
                  color_first ? depth.header.stamp : color.header.stamp,
                  color_first ? depth : color);
        last = std::max(f->color_timestamp, f->timestamp);
        ++frames;
      }
      shift += last - first + 1.0 / 30;
    }
    std::cout << out << ": " << frames << " frames" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "rgbdvo_tum_to_bag: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
