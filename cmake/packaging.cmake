# The Debian package: `cpack -G DEB` in the build folder writes
# sonarmap_<version>_<arch>.deb with everything `cmake --install` installs under /usr: the
# library (static, one libsonarmap_<component>.a per component), its headers and CMake package
# (find_package(sonarmap [COMPONENTS ...])), the `sonarmap` CLI (/usr/bin/sonarmap and the full
# tool it hands every command but `cloud` to, /usr/libexec/sonarmap/sonarmap-full)
# and, when built, the Python module (/usr/lib/python3/dist-packages/sonarmap) and the ROS 1 node
# (/usr/lib/sonarmap_ros, /usr/share/sonarmap_ros: found by rosrun and roslaunch, docs/ros.md; its ROS
# libraries, libroscpp4d and the others, then among the dependencies dpkg-shlibdeps finds).
# `apt-get install ./sonarmap_*.deb` pulls what it needs from Debian: the shared libraries the
# CLI and the module link (dpkg-shlibdeps) and, since the library is static and its headers
# include OpenCV and Eigen, the -dev packages a consumer's build links (sonarmapConfig.cmake's
# find_dependency list; libgeographiclib-dev: the io component links libGeographicLib.so). GDAL is
# linked by the shared libsonarmap_geotiff.so only, so its runtime library (libgdal32, found by
# dpkg-shlibdeps) is all the package needs of it. scripts/test-package.sh checks the package.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME sonarmap)
set(CPACK_PACKAGE_VENDOR "sonarmap")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "Probabilistic 3D occupancy maps from mechanically scanned imaging sonar (library, CLI, Python)")
set(CPACK_PACKAGE_DESCRIPTION
  "sonarmap turns MSIS logs (Tritech Micron/SeaKing, Blue Robotics Ping360) into OctoMap-compatible occupancy octrees: a C++ library with its CMake package, the sonarmap command-line tool and the sonarmap Python module.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "sonarmap developers <sonarmap@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
  "libopencv-dev, libpng-dev, libeigen3-dev, libmatio-dev, libabsl-dev, zlib1g-dev, libicu-dev, libnanoflann-dev, libceres-dev, librosbag-storage-dev, libzstd-dev, liblz4-dev, libsqlite3-dev, libcpp-httplib-dev, libgeographiclib-dev, pkg-config")
if(TARGET sonarmap_python)
  # the extension is built for one Python minor version (its ABI)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
    ", python3 (>= ${SONARMAP_PYTHON_VERSION}), python3 (<< ${SONARMAP_PYTHON_VERSION}.999), python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "cmake, g++, octovis, chromium")
include(CPack)
