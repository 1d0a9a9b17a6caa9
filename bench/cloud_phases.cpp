// sonarmap_cloud_phases IN.graph [RESOLUTION_M]: where the memory and the time of `sonarmap cloud`
// go, phase by phase, in a process that links only the lean components (sonarmap::octree,
// algorithms, io), as the lean `sonarmap` does. After each phase: wall ms, the resident set
// (VmRSS) and its peak so far (VmHWM) from /proc/self/status, and the heap in use (mallinfo2's
// uordblks + hblkhd). Per scan it also prints the bytes of the per-scan key sets the insertion
// built (InsertStats::key_set_bytes: the crossed and the hit voxels) and of the end keys it kept
// (6 B a ray that hits). docs/performance.md,
// "Where the memory and time go", shows its output.
#include <malloc.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/io/scan_graph.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double statusMiB(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.starts_with(field + ":")) return std::atof(line.c_str() + field.size() + 1) / 1024.0;
  }
  return -1.0;
}

void phase(const char* name, Clock::time_point& since) {
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - since).count();
  const struct mallinfo2 heap = mallinfo2();
  std::printf("%-28s %9.2f ms   RSS %7.1f MiB   peak %7.1f MiB   heap %7.1f MiB\n", name, ms, statusMiB("VmRSS"),
              statusMiB("VmHWM"), static_cast<double>(heap.uordblks + heap.hblkhd) / 1048576.0);
  since = Clock::now();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: sonarmap_cloud_phases IN.graph [RESOLUTION_M]\n");
    return 2;
  }
  try {
    auto since = Clock::now();
    phase("at main()", since);
    sonarmap::OcTree16 map(argc == 3 ? std::atof(argv[2]) : 0.05);
    // As `sonarmap cloud`: each scan inserted as soon as it is read.
    sonarmap::readScanGraph(argv[1], [&](sonarmap::Scan&& scan, std::size_t, std::size_t) {
      phase("read a scan", since);
      sonarmap::PointCloud world = std::move(scan.points_m);  // as `sonarmap cloud`: in place
      for (Eigen::Vector3d& p : world) p = scan.sensor_to_world * p;
      phase("scan to the world frame", since);
      // As `sonarmap cloud`: one thread, the points handed over (freed once traced).
      const sonarmap::InsertStats stats =
          sonarmap::insertPointCloudParallel(map, std::move(world), scan.sensor_to_world.translation(), {}, 1);
      phase("insert (trace, sets, tree)", since);
      std::printf("  %zu rays: key sets %.1f MiB, hit keys %.1f MiB\n", stats.rays,
                  static_cast<double>(stats.key_set_bytes) / 1048576.0,
                  static_cast<double>(stats.rays) * sizeof(sonarmap::Key16) / 1048576.0);
    });
    std::printf("  tree: %.1f MiB in use (memoryBytes), %.1f MiB allocated\n",
                static_cast<double>(map.memoryBytes()) / 1048576.0,
                static_cast<double>(map.memoryBytesAllocated()) / 1048576.0);
    const std::string out = (std::filesystem::temp_directory_path() / "sonarmap_cloud_phases.bt").string();
    sonarmap::writeMapFile(map, out);
    phase("write the .bt", since);
    std::filesystem::remove(out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sonarmap_cloud_phases: %s\n", e.what());
    return 1;
  }
  return 0;
}
