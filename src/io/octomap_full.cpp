#include "sonarmap/io/octomap_full.hpp"

#include <algorithm>
#include <fstream>
#include <limits>
#include <vector>

#include "byte_io.hpp"
#include "message_text.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/octomap_header.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kNodeBytes = 5;  // float32 log-odds + child bits

/// Appends the pre-order node records to `buffer`, flushing it to `out` when it grows large.
class FullWriter {
 public:
  FullWriter(const OcTree16& tree, std::ostream& out) : tree_(tree), out_(out) { buffer_.reserve(kFlushBytes + 64); }

  void write() {
    writeNode(tree_.node(kRootRef));
    flush();
  }

 private:
  static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

  void writeNode(const OcTreeNode& node) {
    detail::putF32(buffer_, node.log_odds);
    const auto bits = static_cast<unsigned char>(tree_.childMask(node));
    buffer_.push_back(static_cast<char>(bits));
    if (buffer_.size() >= kFlushBytes) flush();
    for (unsigned i = 0; i < 8; ++i) {
      if ((bits >> i) & 1U) writeNode(tree_.node(tree_.childRef(node, i)));
    }
  }

  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

  const OcTree16& tree_;
  std::ostream& out_;
  std::string buffer_;
};

/// Reads exactly `bytes` bytes, growing the buffer only as data arrives.
std::vector<unsigned char> readExactly(std::istream& in, std::size_t bytes) {
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  std::vector<unsigned char> data;
  while (data.size() < bytes) {
    const std::size_t before = data.size();
    const std::size_t want = std::min(kChunk, bytes - before);
    data.resize(before + want);
    in.read(reinterpret_cast<char*>(data.data() + before), static_cast<std::streamsize>(want));
    data.resize(before + static_cast<std::size_t>(in.gcount()));
    if (data.size() < before + want) break;  // end of stream
  }
  return data;
}

/// Rebuilds the tree from the pre-order stream of 5-byte node records.
class FullReader {
 public:
  FullReader(OcTree16& tree, detail::ByteCursor& in) : tree_(tree), in_(in) {}

  void readNode(NodeRef ref, int depth) {
    const std::size_t at = in_.offset();
    if (in_.remaining() < kNodeBytes) {
      in_.fail("the tree continues past the " + std::to_string(expected_) + " nodes the header's size declares");
    }
    ++nodes_;
    tree_.setLogOdds(ref, in_.finiteF32("log-odds of a node"));
    const std::uint8_t bits = in_.u8("child bits");
    if (bits == 0) return;
    if (depth >= OcTree16::kDepth) in_.failAt(at + 4, "node at depth 16 (the finest level) has children, expected a leaf");
    tree_.createChildren(ref, bits);
    for (unsigned i = 0; i < 8; ++i) {
      if ((bits >> i) & 1U) readNode(tree_.childRef(tree_.node(ref), i), depth + 1);
    }
    tree_.setLogOdds(ref, tree_.aggregateChildren(tree_.node(ref)));
  }

  std::size_t nodes() const { return nodes_; }
  void expect(std::size_t nodes) { expected_ = nodes; }

 private:
  OcTree16& tree_;
  detail::ByteCursor& in_;
  std::size_t nodes_ = 0;
  std::size_t expected_ = 0;
};

}  // namespace

void writeFull(const OcTree16& tree, std::ostream& out, const std::vector<std::string>& comments) {
  writeOctomapHeader(out, kFullFileFirstLine, {"OcTree", tree.counts().nodes, tree.resolution_m(), comments});
  if (!tree.empty()) FullWriter(tree, out).write();
  if (!out) throw FileError("writing the .ot stream failed");
}

void writeFullFile(const OcTree16& tree, const std::string& path, const std::vector<std::string>& comments) {
  writeFileAtomically(path, [&](std::ostream& out) { writeFull(tree, out, comments); });
}

OcTree16 readFull(std::istream& in, const OctreeOptions& options, const std::string& source) {
  const OctomapHeader header = readOctomapHeader(in, kFullFileFirstLine, source);
  if (header.id != "OcTree") {
    throw FileError(source + ": tree type " + detail::quotedForMessage(header.id) + " is not OcTree (only OcTree's .ot layout is read)");
  }
  OcTree16 tree(header.resolution_m, options);
  if (header.size == 0) return tree;
  if (header.size > std::numeric_limits<std::size_t>::max() / kNodeBytes) {
    throw FileError(source + ": header's size " + std::to_string(header.size) + " is not a possible node count");
  }
  const std::streamoff data_start = in.tellg();  // -1 when the stream cannot tell
  const std::size_t bytes = header.size * kNodeBytes;
  const std::vector<unsigned char> data = readExactly(in, bytes);
  const bool known = data_start >= 0;
  detail::ByteCursor cursor(data, source, known ? static_cast<std::size_t>(data_start) : 0, known ? "byte" : "data byte");
  if (data.size() < bytes) {
    cursor.failAt(cursor.offset() + data.size(), "file ends after " + std::to_string(data.size()) +
                                                     " data bytes, expected " + std::to_string(bytes) + " (" +
                                                     std::to_string(header.size) + " nodes × 5 bytes, from the header's size)");
  }
  FullReader reader(tree, cursor);
  reader.expect(header.size);
  reader.readNode(kRootRef, 0);
  if (reader.nodes() != header.size) {
    cursor.fail("tree ends after " + std::to_string(reader.nodes()) + " nodes, expected " + std::to_string(header.size) +
                " (the header's size)");
  }
  return tree;
}

OcTree16 readFullFile(const std::string& path, const OctreeOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError("cannot open '" + path + "' for reading");
  return readFull(in, options, path);
}

}  // namespace sonarmap
