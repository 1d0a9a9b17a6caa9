// libFuzzer harness: ROS 1 bag bytes → readRosBag (the container through rosbag_storage, each
// message decoded from the definition the bag stores), then the sonar log it gives.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile file(".bag");
  const std::string& path = file.write(data, size);
  return sonarmap::fuzz::expectReadOrError([&] { (void)sonarmap::readRosBag(path); });
}
