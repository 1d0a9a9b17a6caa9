#pragma once
/// @file octomap_full.hpp
/// OctoMap's full tree format (`.ot`, OctoMap 1.9 `AbstractOcTree::write/read` for `OcTree`;
/// `../shared/docs/formats.md`): every node with its exact float32 log-odds, unlike `.bt`.
///
/// Layout: the ASCII header (first line `# Octomap OcTree file`, then `id OcTree`, `size N`,
/// `res R`, `data`; see octomap_header.hpp), then the N nodes in depth-first pre-order from the
/// root, 5 bytes each: the float32 log-odds (little-endian), then one byte whose bit i is set when
/// child i exists; the existing children follow in order 0…7. An empty tree is `size 0` and no
/// data. Only depth-16 `OcTree` files (not `ColorOcTree`, `OcTreeStamped`…) have this layout.

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// Writes `tree` in `.ot` layout with every node's log-odds as stored. The tree is not modified
/// (no thresholding, no pruning). @throws FileError when the stream fails.
void writeFull(const OcTree16& tree, std::ostream& out, const std::vector<std::string>& comments = {});

/// Writes `tree` to `path` atomically (temporary file + rename).
/// @throws FileError when the file cannot be written; an existing file is then left untouched.
void writeFullFile(const OcTree16& tree, const std::string& path, const std::vector<std::string>& comments = {});

/// Reads a `.ot` tree from `in` into a new tree with `options`. Leaves keep the file's log-odds
/// exactly and the structure is kept as stored (nothing is pruned); inner nodes get the aggregate
/// of their children by `options.aggregation` — for OctoMap's trees (max) that is the value stored.
/// Reads exactly the `size` × 5 data bytes, growing its buffer as data arrives, so a corrupt
/// `size` cannot make it allocate more than the stream holds.
/// @param source name used in error messages (the file name).
/// @throws FileError when the header is malformed (see readOctomapHeader) or its id is not
///         `OcTree`, the data ends before `size` nodes, a log-odds is NaN or infinite, a node at
///         depth 16 has children, or the tree holds fewer nodes than `size` says. Messages give
///         the byte offset in the file (in the data when the stream cannot tell its position).
/// @throws ValueError when the resolution is not finite and positive.
OcTree16 readFull(std::istream& in, const OctreeOptions& options = {}, const std::string& source = "<stream>");

/// Reads a `.ot` file. @throws FileError as readFull, or when the file cannot be opened.
OcTree16 readFullFile(const std::string& path, const OctreeOptions& options = {});

}  // namespace sonarmap
