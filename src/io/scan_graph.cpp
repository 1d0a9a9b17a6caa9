#include "sonarmap/io/scan_graph.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "byte_io.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {
namespace {

// Sizes of the fixed-size parts of the layout, in bytes.
constexpr std::uint64_t kPointBytes = 4 + 3 * 8;                // int32 3, float64 x y z
constexpr std::uint64_t kPoseBytes = 4 + 3 * 8 + 4 + 4 * 8;     // vector + quaternion
constexpr std::uint64_t kNodeFixedBytes = 4 + kPoseBytes + 4;   // point count, pose, id
constexpr std::uint64_t kEdgeBytes = 4 + 4 + kPoseBytes + 8;    // two ids, pose, weight
constexpr std::int32_t kVectorMarker = 3;
constexpr std::int32_t kQuaternionMarker = 4;
#ifdef MADV_POPULATE_READ
constexpr int kPopulateRead = MADV_POPULATE_READ;
#else
constexpr int kPopulateRead = 22;  // Linux 5.14's value; an older kernel answers EINVAL
#endif

void expectMarker(detail::ByteCursor& in, std::int32_t expected, const std::string& what) {
  const std::size_t at = in.offset();
  const std::int32_t marker = in.i32("size marker of " + what);
  if (marker != expected) {
    in.failAt(at, "size marker of " + what + " is " + std::to_string(marker) + ", expected " + std::to_string(expected));
  }
}

Eigen::Vector3d readVector(detail::ByteCursor& in, const std::string& what) {
  expectMarker(in, kVectorMarker, what);
  Eigen::Vector3d v;
  v.x() = in.finiteF64("x of " + what);
  v.y() = in.finiteF64("y of " + what);
  v.z() = in.finiteF64("z of " + what);
  return v;
}

/// A node's `count` points, in one block of bytes known to be there (requireCount): only a
/// marker or a value can fail, and the message naming the point is built only then.
void readPoints(detail::ByteCursor& in, std::uint32_t count, const std::string& node, std::vector<Eigen::Vector3d>& points) {
  const std::size_t first = in.offset();
  const std::span<const unsigned char> bytes = in.take(count * kPointBytes, "points of " + node);
  points.resize(count);
  for (std::uint32_t p = 0; p < count; ++p) {
    const unsigned char* point = bytes.data() + p * kPointBytes;
    const std::size_t at = first + p * kPointBytes;
    auto name = [&] { return "point " + std::to_string(p) + " of " + node; };
    const auto marker = static_cast<std::int32_t>(detail::u32At(point));
    if (marker != kVectorMarker) {
      in.failAt(at, "size marker of " + name() + " is " + std::to_string(marker) + ", expected " + std::to_string(kVectorMarker));
    }
    Eigen::Vector3d& v = points[p];
    for (int axis = 0; axis < 3; ++axis) {
      v[axis] = std::bit_cast<double>(detail::u64At(point + 4 + 8 * axis));
      if (!std::isfinite(v[axis])) {
        in.failAt(at + 4 + 8 * static_cast<std::size_t>(axis),
                  std::string(1, "xyz"[axis]) + " of " + name() + " is " + std::to_string(v[axis]) + ", expected a finite number");
      }
    }
  }
}

Eigen::Isometry3d readPose(detail::ByteCursor& in, const std::string& what) {
  const Eigen::Vector3d translation = readVector(in, "translation of " + what);
  const std::size_t at = in.offset();
  expectMarker(in, kQuaternionMarker, "rotation of " + what);
  const double w = in.finiteF64("qw of " + what);
  const double x = in.finiteF64("qx of " + what);
  const double y = in.finiteF64("qy of " + what);
  const double z = in.finiteF64("qz of " + what);
  const Eigen::Quaterniond q(w, x, y, z);
  const double norm = q.norm();
  if (!(std::abs(norm - 1.0) <= kScanGraphQuaternionTolerance)) {
    in.failAt(at, "rotation of " + what + " has norm " + std::to_string(norm) + ", expected a unit quaternion");
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = translation;
  return pose;
}

/// Checks that `count` items of `item_bytes` each, plus `after` more bytes, fit in what is left.
void requireCount(const detail::ByteCursor& in, std::uint64_t count, std::uint64_t item_bytes, std::uint64_t after,
                  const std::string& what) {
  const std::uint64_t left = in.remaining();
  if (count > left / item_bytes || count * item_bytes + after > left) {
    in.fail(what + " declares " + std::to_string(count) + " (" + std::to_string(item_bytes) + " bytes each) but only " +
            std::to_string(left) + " bytes are left");
  }
}

/// Parses `data` node by node, handing each scan to `visit` as soon as it is read, then checks
/// the edges. `consumed(offset)` is called after each node with the offset of its last byte + 1
/// and `upcoming(offset, bytes)` before a node's points are read, so that a mapped file's pages
/// can be brought in and dropped around the cursor.
template <class Upcoming, class Consumed>
void parseScanGraph(std::span<const unsigned char> data, const std::string& source, const ScanVisitor& visit,
                    Upcoming&& upcoming, Consumed&& consumed) {
  detail::ByteCursor in(data, source);
  const std::uint32_t node_count = in.u32("node count");
  // Each node takes at least kNodeFixedBytes; the edge count follows the nodes.
  requireCount(in, node_count, kNodeFixedBytes, 4, "node count");
  std::vector<std::uint32_t> ids;
  ids.reserve(node_count);
  for (std::uint32_t n = 0; n < node_count; ++n) {
    const std::string node = "node " + std::to_string(n);
    const std::uint32_t point_count = in.u32("point count of " + node);
    requireCount(in, point_count, kPointBytes, kPoseBytes + 4, "point count of " + node);
    upcoming(in.offset(), point_count * kPointBytes + kPoseBytes + 4);
    Scan scan;
    readPoints(in, point_count, node, scan.points_m);
    scan.sensor_to_world = readPose(in, "pose of " + node);
    ids.push_back(in.u32("id of " + node));
    consumed(in.offset());
    visit(std::move(scan), n, node_count);
  }
  std::sort(ids.begin(), ids.end());
  const std::uint32_t edge_count = in.u32("edge count");
  requireCount(in, edge_count, kEdgeBytes, 0, "edge count");
  for (std::uint32_t e = 0; e < edge_count; ++e) {
    const std::string edge = "edge " + std::to_string(e);
    for (const char* end : {"first", "second"}) {
      const std::size_t at = in.offset();
      const std::uint32_t id = in.u32(std::string(end) + " node id of " + edge);
      if (!std::binary_search(ids.begin(), ids.end(), id)) {
        in.failAt(at, std::string(end) + " node id of " + edge + " is " + std::to_string(id) + ", not the id of a node in the file");
      }
    }
    readPose(in, "constraint of " + edge);
    in.finiteF64("weight of " + edge);
  }
  if (in.remaining() != 0) in.fail(std::to_string(in.remaining()) + " unexpected bytes after the last edge, expected the end of the file");
}

/// Collects every scan in a vector.
struct Collect {
  std::vector<Scan>* scans;
  void operator()(Scan&& scan, std::size_t index, std::size_t count) const {
    if (index == 0) scans->reserve(count);
    scans->push_back(std::move(scan));
  }
};

void checkFinite(const Eigen::Vector3d& v, const std::string& what) {
  if (!v.allFinite()) throw ValueError("scan graph not written: " + what + " is not finite");
}

}  // namespace

void readScanGraph(std::istream& in, const ScanVisitor& visit, const std::string& source) {
  std::vector<unsigned char> data;
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  while (in) {  // in chunks: only what the stream holds is allocated
    const std::size_t before = data.size();
    data.resize(before + kChunk);
    in.read(reinterpret_cast<char*>(data.data() + before), static_cast<std::streamsize>(kChunk));
    data.resize(before + static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw FileError(source + ": reading failed");
  parseScanGraph(data, source, visit, [](std::size_t, std::size_t) {}, [](std::size_t) {});
}

std::vector<Scan> readScanGraph(std::istream& in, const std::string& source) {
  std::vector<Scan> scans;
  readScanGraph(in, ScanVisitor(Collect{&scans}), source);
  return scans;
}

void readScanGraph(const std::string& path, const ScanVisitor& visit) {
  // A regular file is parsed where the system keeps it (mmap of the page cache): a copy in a
  // buffer costs a page fault for each of its pages, and those faults made reading a 2.5 MB graph
  // take 4 times as long. Each node's pages are mapped in one call before it is parsed
  // (MADV_POPULATE_READ, Linux 5.14; without it they fault in one by one) and dropped from the
  // process once it is (MADV_DONTNEED: a clean file page is only unmapped), so the file's share of
  // the resident set is one node, not the whole file. Anything else (a pipe, a system without the
  // mapping) is read as a stream. As with any mapped file, another process truncating the file
  // while it is parsed ends this one (SIGBUS).
  std::error_code error;
  if (std::filesystem::is_regular_file(path, error)) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw FileError("cannot open '" + path + "' for reading");
    struct stat status {};
    void* mapped = MAP_FAILED;
    std::size_t size = 0;
    if (::fstat(fd, &status) == 0 && status.st_size > 0) {
      size = static_cast<std::size_t>(status.st_size);
      mapped = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    }
    ::close(fd);
    if (mapped != MAP_FAILED) {
      struct Unmap {
        void* at;
        std::size_t bytes;
        ~Unmap() { ::munmap(at, bytes); }
      } const unmap{mapped, size};
      auto* const base = static_cast<unsigned char*>(mapped);
      const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
      std::size_t dropped = 0;  // bytes before this offset are no longer mapped in
      const auto upcoming = [&](std::size_t offset, std::size_t bytes) {
        const std::size_t from = offset / page * page;
        (void)::madvise(base + from, std::min(size, offset + bytes) - from, kPopulateRead);  // a hint: may fail
      };
      const auto consumed = [&](std::size_t offset) {
        const std::size_t until = offset / page * page;
        if (until > dropped) (void)::madvise(base + dropped, until - dropped, MADV_DONTNEED);
        dropped = std::max(dropped, until);
      };
      parseScanGraph(std::span<const unsigned char>(base, size), path, visit, upcoming, consumed);
      return;
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError("cannot open '" + path + "' for reading");
  readScanGraph(in, visit, path);
}

std::vector<Scan> readScanGraph(const std::string& path) {
  std::vector<Scan> scans;
  readScanGraph(path, ScanVisitor(Collect{&scans}));
  return scans;
}

void writeScanGraph(std::ostream& out, const std::vector<Scan>& scans) {
  constexpr std::size_t kMaxCount = std::numeric_limits<std::uint32_t>::max();
  if (scans.size() > kMaxCount) throw ValueError("scan graph not written: more than 2^32 - 1 scans");
  // Validate everything first: nothing is written for an invalid input.
  for (std::size_t n = 0; n < scans.size(); ++n) {
    const Scan& scan = scans[n];
    const std::string node = "scan " + std::to_string(n);
    if (scan.points_m.size() > kMaxCount) throw ValueError("scan graph not written: " + node + " has more than 2^32 - 1 points");
    for (std::size_t p = 0; p < scan.points_m.size(); ++p) checkFinite(scan.points_m[p], "point " + std::to_string(p) + " of " + node);
    checkFinite(scan.sensor_to_world.translation(), "translation of " + node);
    if (!scan.sensor_to_world.linear().allFinite()) throw ValueError("scan graph not written: rotation of " + node + " is not finite");
  }
  auto putVector = [](std::string& bytes, const Eigen::Vector3d& v) {
    detail::putI32(bytes, kVectorMarker);
    for (int i = 0; i < 3; ++i) detail::putF64(bytes, v[i]);
  };
  std::string bytes;
  detail::putU32(bytes, static_cast<std::uint32_t>(scans.size()));
  for (std::size_t n = 0; n < scans.size(); ++n) {
    const Scan& scan = scans[n];
    bytes.reserve(bytes.size() + kNodeFixedBytes + kPointBytes * scan.points_m.size());
    detail::putU32(bytes, static_cast<std::uint32_t>(scan.points_m.size()));
    for (const Eigen::Vector3d& point : scan.points_m) putVector(bytes, point);
    putVector(bytes, scan.sensor_to_world.translation());
    const Eigen::Quaterniond q = Eigen::Quaterniond(scan.sensor_to_world.linear()).normalized();
    detail::putI32(bytes, kQuaternionMarker);
    for (const double value : {q.w(), q.x(), q.y(), q.z()}) detail::putF64(bytes, value);
    detail::putU32(bytes, static_cast<std::uint32_t>(n));  // id
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    bytes.clear();
  }
  detail::putU32(bytes, 0);  // no edges
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw FileError("writing the .graph stream failed");
}

void writeScanGraph(const std::string& path, const std::vector<Scan>& scans) {
  writeFileAtomically(path, [&](std::ostream& out) { writeScanGraph(out, scans); });
}

}  // namespace sonarmap
