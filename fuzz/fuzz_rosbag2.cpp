// libFuzzer harness: rosbag2 SQLite database bytes (ROS 2 logs before Iron) → readRosBag (the
// tables read through libsqlite3, each message CDR-decoded from its built-in or stored definition),
// listRosBagTopics and readRosBagNavigation.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile file(".db3");
  const std::string& path = file.write(data, size);
  sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::readRosBag(path); });
  sonarmap::fuzz::expectReadOrError([&] { sonarmap::fuzz::readTwice(*sonarmap::openRosBag(path)); });
  sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::listRosBagTopics(path); });
  return sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::readRosBagNavigation(path); });
}
