#pragma once
/// @file scan_graph.hpp
/// OctoMap's binary scan graph (`.graph`, OctoMap 1.9 `ScanGraph::readBinary/writeBinary`;
/// layout in `../shared/docs/formats.md`): 3D scans, each a point cloud in the sensor frame with
/// the sensor's pose in the world, plus edges (pose constraints between scans).
///
/// Layout, little-endian, no header:
/// ```
/// uint32 node_count
/// node_count ×  uint32 point_count, point_count × (int32 3, float64 x y z),
///               pose = int32 3, float64 tx ty tz, int32 4, float64 qw qx qy qz,  uint32 id
/// uint32 edge_count
/// edge_count ×  uint32 first_id, uint32 second_id, pose, float64 weight
/// ```
/// Only the scans are returned, in file order; node ids and edges are validated and dropped.

#include <istream>
#include <ostream>
#include <string>
#include <cstddef>
#include <functional>
#include <vector>

#include "sonarmap/core/point_cloud.hpp"

namespace sonarmap {

/// Largest deviation of a stored quaternion's norm from 1 that is accepted (and normalised away).
/// OctoMap keeps quaternions as float32, so its files deviate by about 1e-7.
inline constexpr double kScanGraphQuaternionTolerance = 1e-3;

/// Called with each scan of a `.graph` as it is read: the scan, its index (0 … count − 1) and the
/// file's node count.
using ScanVisitor = std::function<void(Scan&& scan, std::size_t index, std::size_t count)>;

/// Reads every scan of a `.graph` file: points in metres in the sensor frame (`Scan::points_m`)
/// and the sensor pose in the world (`Scan::sensor_to_world`: rotation from the quaternion,
/// normalised, then the translation in metres), in the file's node order.
/// Every count is checked against the bytes left before anything is allocated, so a corrupt
/// count cannot make the reader allocate more than the file's size. A regular file is parsed
/// through a read-only mapping (POSIX mmap), others (a pipe) as readScanGraph(std::istream&);
/// as with any mapped file, a file truncated by another process while it is parsed raises SIGBUS.
/// @throws FileError (naming the file, the byte offset and what was expected there) when the file
///         cannot be opened, ends early, a size marker is not 3 (vectors) or 4 (quaternions), a
///         number is NaN or infinite, a quaternion's norm is not within
///         kScanGraphQuaternionTolerance of 1 (a zero quaternion included), an edge names a node
///         id that is not in the file, or bytes follow the last edge.
std::vector<Scan> readScanGraph(const std::string& path);

/// Reads a `.graph` file scan by scan, calling `visit` with each scan once it is read, before the
/// next is read: one scan's points are in memory at a time, and of a mapped file only the node
/// being read is resident. The edges are checked after the last scan, so an invalid edge throws
/// after every scan was visited (a caller writes its output only once this returns).
/// @throws FileError as readScanGraph(path); what `visit` throws propagates.
void readScanGraph(const std::string& path, const ScanVisitor& visit);

/// As readScanGraph(path, visit), from the rest of `in`. @param source name used in messages.
void readScanGraph(std::istream& in, const ScanVisitor& visit, const std::string& source = "<stream>");

/// Reads a `.graph` from the rest of `in` (to its end). @param source name used in messages.
/// @throws FileError as readScanGraph(path).
std::vector<Scan> readScanGraph(std::istream& in, const std::string& source = "<stream>");

/// Writes `scans` as a `.graph` that OctoMap's `ScanGraph::readBinary` reads: node ids 0 … n−1 in
/// order, no edges. The rotation is written as the unit quaternion of
/// `sensor_to_world.linear()` (which must be a rotation). Points are written as float64;
/// OctoMap keeps them as float32 when it reads them.
/// @throws ValueError when a point or pose value is not finite or a count exceeds 2^32 − 1.
/// @throws FileError when the stream fails.
void writeScanGraph(std::ostream& out, const std::vector<Scan>& scans);

/// Writes `scans` to `path` atomically (temporary file + rename): an existing file is left
/// untouched on any error. @throws ValueError, FileError as writeScanGraph(stream).
void writeScanGraph(const std::string& path, const std::vector<Scan>& scans);

}  // namespace sonarmap
