// `rgbdvo info RECORDING`: what a recording holds (a bag's topics, a folder's frames).
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "recording_input.hpp"
#include "rgbdvo/io/ros2_bag.hpp"
#include "rgbdvo/sources/open_source.hpp"
#ifdef RGBDVO_WITH_ROSBAG
#include "rgbdvo/sources/rosbag_source.hpp"
#endif

namespace rgbdvo::cli {
namespace {

void PrintBag(const std::string& path) {
#ifdef RGBDVO_WITH_ROSBAG
  const std::vector<BagTopic> topics = ListBagTopics(path);
  std::cout << path << ": ROS 1 bag, " << topics.size() << " topics\n";
  std::cout << std::left << std::setw(36) << "topic" << std::setw(32) << "type" << std::right
            << std::setw(9) << "messages" << std::setw(10) << "rate Hz"
            << "\n";
  for (const BagTopic& t : topics)
    std::cout << std::left << std::setw(36) << t.topic << std::setw(32) << t.type << std::right
              << std::setw(9) << t.messages << std::setw(10) << std::fixed << std::setprecision(2)
              << t.RateHz() << "\n";
  std::cout << std::flush;
#else
  throw std::runtime_error(path + ": a ROS bag, but this rgbdvo was built without ROS bag support");
#endif
}

void PrintRos2Bag(const std::string& path) {
  const std::vector<Ros2Topic> topics = ListRos2Topics(path);
  std::cout << path << ": ROS 2 bag, " << topics.size() << " topics\n";
  std::cout << std::left << std::setw(36) << "topic" << std::setw(34) << "type" << std::setw(6)
            << "ser." << std::right << std::setw(9) << "messages" << std::setw(10) << "rate Hz"
            << "\n";
  for (const Ros2Topic& t : topics)
    std::cout << std::left << std::setw(36) << t.name << std::setw(34) << t.type << std::setw(6)
              << t.serialization << std::right << std::setw(9) << t.messages << std::setw(10)
              << std::fixed << std::setprecision(2) << t.RateHz() << "\n";
  std::cout << std::flush;
}

}  // namespace

void AddInfoCommand(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "what a recording holds: a ROS bag's topics, types, counts and rates; a folder's frames");
  cmd->add_option("recording", *path,
                  "recording folder, ROS 1 bag, or ROS 2 bag (.mcap, .db3 or rosbag2 folder)")
      ->required();
  cmd->callback([path] {
    if (IsRosbagFile(*path)) return PrintBag(*path);
    if (IsRos2Bag(*path)) return PrintRos2Bag(*path);
    std::cout << OpenRecording(*path, SourceOptions())->Describe() << std::endl;
  });
}

}  // namespace rgbdvo::cli
