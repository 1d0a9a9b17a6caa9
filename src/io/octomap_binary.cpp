#include "sonarmap/io/octomap_binary.hpp"

#include <bit>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

#include "message_text.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/octomap_header.hpp"

namespace sonarmap {
namespace {

// Two-bit child codes of the .bt format.
constexpr unsigned kUnknown = 0, kFreeLeaf = 1, kOccupiedLeaf = 2, kInner = 3;

unsigned childCode(const OcTree16& tree, const OcTreeNode& child) {
  if (!child.exists()) return kUnknown;
  if (child.hasChildren()) return kInner;
  return tree.model().isOccupied(child.log_odds) ? kOccupiedLeaf : kFreeLeaf;
}

/// Writes at `out` the 2-byte child codes of `node` (which has children) and of its inner
/// descendants, in pre-order, and returns the number of nodes below it: the header's count, found on
/// the way instead of by a walk of its own. A node's existing children are consecutive slots, in
/// child order (NodePool), so only they are visited. `out` has room for 2 bytes per inner node.
std::size_t writeNode(const OcTree16& tree, const OcTreeNode& node, unsigned char*& out) {
  const unsigned mask = tree.childMask(node);
  const NodeRef first = tree.childRef(node, static_cast<unsigned>(std::countr_zero(mask)));
  unsigned bits = 0;
  unsigned inner = 0;  // bit i: child i is an inner node
  NodeRef child = first;
  for (unsigned rest = mask; rest != 0; rest &= rest - 1, ++child) {
    const auto i = static_cast<unsigned>(std::countr_zero(rest));
    const unsigned code = childCode(tree, tree.node(child));
    bits |= code << (2 * i);
    inner |= code == kInner ? 1U << i : 0U;
  }
  std::size_t below = child - first;
  *out++ = static_cast<unsigned char>(bits & 0xFFU);
  *out++ = static_cast<unsigned char>(bits >> 8);
  child = first;
  for (unsigned rest = mask; rest != 0; rest &= rest - 1, ++child) {
    if (((inner >> std::countr_zero(rest)) & 1U) != 0) below += writeNode(tree, tree.node(child), out);
  }
  return below;
}

/// Rebuilds the tree from the pre-order stream of 2-byte child codes.
class BinaryReader {
 public:
  BinaryReader(OcTree16& tree, const std::vector<unsigned char>& data, const std::string& source)
      : tree_(tree), data_(data), source_(source) {}

  std::size_t read() {
    tree_.setLogOdds(kRootRef, 0.0F);
    readNode(kRootRef, 0);
    return nodes_;
  }

 private:
  void readNode(NodeRef ref, int depth) {
    ++nodes_;
    if (offset_ + 2 > data_.size()) {
      throw FileError(source_ + ": data ends at byte " + std::to_string(offset_) + " inside node " + std::to_string(nodes_));
    }
    if (depth >= OcTree16::kDepth) {
      throw FileError(source_ + ": inner node below the finest level (depth 16) at data byte " + std::to_string(offset_));
    }
    const unsigned bits = data_[offset_] | (static_cast<unsigned>(data_[offset_ + 1]) << 8);
    offset_ += 2;
    unsigned mask = 0;  // children that exist: code not kUnknown
    for (unsigned i = 0; i < 8; ++i) mask |= ((bits >> (2 * i)) & 3U) != kUnknown ? 1U << i : 0U;
    tree_.createChildren(ref, mask);
    for (unsigned i = 0; i < 8; ++i) {
      const unsigned code = (bits >> (2 * i)) & 3U;
      const NodeRef child = tree_.childRef(tree_.node(ref), i);
      if (code == kFreeLeaf) tree_.setLogOdds(child, tree_.model().clamp_min);
      if (code == kOccupiedLeaf) tree_.setLogOdds(child, tree_.model().clamp_max);
      if (code == kInner) {
        tree_.setLogOdds(child, 0.0F);
        readNode(child, depth + 1);
      }
      if (code == kFreeLeaf || code == kOccupiedLeaf) ++nodes_;
    }
    tree_.setLogOdds(ref, tree_.aggregateChildren(tree_.node(ref)));
  }

  OcTree16& tree_;
  const std::vector<unsigned char>& data_;
  const std::string& source_;
  std::size_t offset_ = 0;
  std::size_t nodes_ = 0;
};

}  // namespace

void writeBinary(const OcTree16& tree, std::ostream& out, const std::vector<std::string>& comments) {
  // The data first: it gives the node count the header needs. Every node is an 8-byte slot, so
  // memoryBytes() / 4 bounds the 2 bytes of each inner node; the buffer is not filled beforehand,
  // so only what is written becomes resident.
  const std::unique_ptr<unsigned char[]> data(new unsigned char[tree.memoryBytes() / 4 + 2]);
  unsigned char* end = data.get();
  std::size_t nodes = 0;
  const OcTreeNode& root = tree.node(kRootRef);
  if (root.exists()) nodes = 1 + (root.hasChildren() ? writeNode(tree, root, end) : 0);
  writeOctomapHeader(out, kBinaryFileFirstLine, {"OcTree", nodes, tree.resolution_m(), comments});
  out.write(reinterpret_cast<const char*>(data.get()), end - data.get());
  if (!out) throw FileError("writing the .bt stream failed");
}

void writeBinaryFile(const OcTree16& tree, const std::string& path, const std::vector<std::string>& comments) {
  writeFileAtomically(path, [&](std::ostream& out) { writeBinary(tree, out, comments); });
}

OcTree16 readBinary(std::istream& in, const OctreeOptions& options, const std::string& source) {
  const OctomapHeader header = readOctomapHeader(in, kBinaryFileFirstLine, source);
  if (header.id != "OcTree") throw FileError(source + ": tree type " + detail::quotedForMessage(header.id) + " is not OcTree");
  OcTree16 tree(header.resolution_m, options);
  if (header.size == 0) return tree;
  const std::vector<unsigned char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Each inner node takes 2 bytes and has 1 to 8 children, so D data bytes describe 2 to 1 + 4·D
  // nodes: a larger size is rejected before the tree is built.
  if (data.size() < 2) throw FileError(source + ": header says " + std::to_string(header.size) + " nodes but no data follows");
  if (header.size > 1 + 4 * data.size()) {
    throw FileError(source + ": header says " + std::to_string(header.size) + " nodes but the " +
                    std::to_string(data.size()) + " data bytes after the header describe at most " +
                    std::to_string(1 + 4 * data.size()) + " (2 bytes per inner node of at most 8 children)");
  }
  const std::size_t nodes = BinaryReader(tree, data, source).read();
  if (nodes != header.size) {
    throw FileError(source + ": header says " + std::to_string(header.size) + " nodes, data holds " + std::to_string(nodes));
  }
  return tree;
}

OcTree16 readBinaryFile(const std::string& path, const OctreeOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError("cannot open '" + path + "' for reading");
  return readBinary(in, options, path);
}

}  // namespace sonarmap
