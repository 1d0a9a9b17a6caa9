// libFuzzer harness: ROS 1 bag bytes → readRosBag (the container walked, then read through
// rosbag_storage when whole and indexed, else from the walk up to its damage: ros_bag_scan.hpp;
// each message decoded from the definition the bag stores), listRosBagTopics, readRosBagMounting
// (/tf_static) and readRosBagNavigation.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/ros_bag_mounting.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile file(".bag");
  const std::string& path = file.write(data, size);
  sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::readRosBag(path); });
  sonarmap::fuzz::expectReadOrError([&] { sonarmap::fuzz::readTwice(*sonarmap::openRosBag(path)); });
  sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::listRosBagTopics(path); });
  sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::readRosBagMounting(path, "sonar", "base_link"); });
  return sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::readRosBagNavigation(path); });
}
