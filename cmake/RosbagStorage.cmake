# Debian's ROS 1 bag library (librosbag-storage-dev: the bag container, its chunks, bz2 and lz4
# compression and its index, with libbz2) as one imported target, sonarmap_rosbag_storage. Its own CMake config
# is catkin's and runs ament's Python, and its pkg-config file requires a pluginlib.pc that
# Debian's ROS 2 pluginlib does not install; so the libraries, and the ROS 2 style nested include
# folders that rosbag/bag.h reaches through pluginlib, are found here. Included by the build and by
# the installed sonarmapConfig.cmake.
if(NOT TARGET sonarmap_rosbag_storage)
  find_path(SONARMAP_ROSBAG_INCLUDE_DIR rosbag/bag.h REQUIRED)
  set(_sonarmap_rosbag_includes ${SONARMAP_ROSBAG_INCLUDE_DIR})
  # header each nested folder must hold, and the folder
  foreach(_pair "pluginlib/class_loader.hpp;pluginlib" "class_loader/class_loader.hpp;class_loader"
                "ament_index_cpp/get_package_prefix.hpp;ament_index_cpp" "rcpputils/shared_library.hpp;rcpputils"
                "rcutils/allocator.h;rcutils")
    list(GET _pair 0 _header)
    list(GET _pair 1 _folder)
    find_path(SONARMAP_ROSBAG_${_folder}_DIR ${_header} PATH_SUFFIXES ${_folder} REQUIRED)
    list(APPEND _sonarmap_rosbag_includes ${SONARMAP_ROSBAG_${_folder}_DIR})
  endforeach()
  set(_sonarmap_rosbag_libraries)
  foreach(_name rosbag_storage roscpp_serialization rostime cpp_common roslz4 console_bridge boost_filesystem)
    find_library(SONARMAP_ROSBAG_${_name}_LIBRARY ${_name} REQUIRED)
    list(APPEND _sonarmap_rosbag_libraries ${SONARMAP_ROSBAG_${_name}_LIBRARY})
  endforeach()
  # libbz2 and roslz4 decompress a chunk once more to check it (src/formats/ros_bag_check.hpp)
  find_package(BZip2 REQUIRED)
  list(APPEND _sonarmap_rosbag_libraries BZip2::BZip2)
  add_library(sonarmap_rosbag_storage INTERFACE IMPORTED)
  set_target_properties(sonarmap_rosbag_storage PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${_sonarmap_rosbag_includes}"
    INTERFACE_LINK_LIBRARIES "${_sonarmap_rosbag_libraries}")
endif()
