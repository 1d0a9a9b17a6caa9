#pragma once
/// @file octomap_binary.hpp
/// OctoMap's binary tree format (`.bt`, OctoMap 1.9; `../shared/docs/formats.md`, paper §7).
///
/// A `.bt` file stores only the maximum-likelihood state: each node is unknown, free, occupied or
/// an inner node. Leaves are written as occupied when their log-odds is above the occupied
/// threshold and as free otherwise (OctoMap's `isNodeOccupied`). On reading, free leaves get the
/// lower clamping log-odds, occupied leaves the upper one, inner nodes the aggregate of their
/// children. Only depth-16 trees have this layout.

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// Writes `tree` in `.bt` layout, `comments` as header comment lines (octomap_header.hpp). The
/// tree is not modified (no thresholding, no pruning).
/// @throws FileError when the stream fails; ValueError for a comment holding a line break.
void writeBinary(const OcTree16& tree, std::ostream& out, const std::vector<std::string>& comments = {});

/// Writes `tree` to `path` atomically (temporary file + rename).
/// @throws FileError when the file cannot be written; an existing file is then left untouched.
void writeBinaryFile(const OcTree16& tree, const std::string& path, const std::vector<std::string>& comments = {});

/// Reads a `.bt` stream into a new tree with the given options (sensor model, aggregation).
/// @param source name used in error messages (the file name).
/// Reads the data bytes that follow the header (no more than the stream holds) and checks `size`
/// against them before building anything: 2 bytes per inner node of at most 8 children describe
/// at most 1 + 4 × bytes nodes, so a corrupt `size` of 10^9 is rejected at once.
/// @throws FileError on a wrong first line, a missing or malformed `id`/`size`/`res`/`data`
///         header, an id other than `OcTree`, a `size` more than the data can describe,
///         truncated data, a node count that differs from `size`, or an inner-node code at the
///         finest level. Messages name `source`; text quoted from the file is escaped and cut. @throws ValueError on a resolution
///         that is not finite and positive.
OcTree16 readBinary(std::istream& in, const OctreeOptions& options = {}, const std::string& source = "<stream>");

/// Reads a `.bt` file. @throws FileError as readBinary, or when the file cannot be opened.
OcTree16 readBinaryFile(const std::string& path, const OctreeOptions& options = {});

}  // namespace sonarmap
