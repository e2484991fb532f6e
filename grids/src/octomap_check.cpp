// The node data of an OctoMap file walked to its end before octomap reads it (see
// octomap_file.hpp). The layouts are octomap's (1.9): a .bt is written by
// OccupancyOcTreeBase::writeBinaryNode, a .ot by OcTreeBaseImpl::writeNodesRecurs, both depth
// first from the root.
#include <cmath>
#include <cstring>
#include <string>

#include "gridloc/grids/error.hpp"
#include "octomap_file.hpp"

namespace gridloc::octomap_detail {
namespace {

// Thrown inside the walk when the data ends in the middle of a node.
struct DataEnds {};

// Walks one file's data, counting the nodes read whole: a .ot node once its value and child
// byte are read, a .bt leaf once its parent's codes are, a .bt inner node once its own are.
class DataWalker {
 public:
  DataWalker(const std::string& path, const OctomapFile& file) : path_(path), file_(file) {}

  /// The number of nodes in the data, which is read to the end of the tree.
  std::uint64_t walk() {
    if (file_.data.empty() && file_.size == 0) return 0;
    if (file_.binary) {
      binary_node(0);
    } else {
      full_node(0);
    }
    return nodes_;
  }
  std::uint64_t nodes() const { return nodes_; }
  std::size_t end() const { return pos_; }

 private:
  // A .bt inner node: two bytes, children 0-3 in the first, 4-7 in the second, child i's code
  // in bits 2i (low) and 2i + 1: 0 none, 1 free leaf, 2 occupied leaf, 3 inner node (whose own
  // two bytes follow, in child order, after this node's).
  void binary_node(int depth) {
    const unsigned low = byte();
    const unsigned codes = low | byte() << 8;
    if (codes == 0 && depth > 0) fail("an inner node without children");
    ++nodes_;
    for (int child = 0; child < 8; ++child) {
      const unsigned code = (codes >> (2 * child)) & 3u;
      nodes_ += code == 1u || code == 2u;
    }
    for (int child = 0; child < 8; ++child) {
      if (((codes >> (2 * child)) & 3u) != 3u) continue;
      if (depth + 1 == kTreeDepth) fail("a node below the leaf level (depth 16)");
      binary_node(depth + 1);
    }
  }

  // A .ot node: its value (a float log-odds for an OcTree), then one byte whose bit i says
  // child i follows, each child a node again.
  void full_node(int depth) {
    float log_odds = 0.0f;
    if (file_.data.size() - pos_ < sizeof log_odds) throw DataEnds{};
    std::memcpy(&log_odds, file_.data.data() + pos_, sizeof log_odds);
    pos_ += sizeof log_odds;
    if (!std::isfinite(log_odds)) fail("a node whose log-odds is not finite");
    const unsigned children = byte();
    if (children != 0 && depth == kTreeDepth) fail("a node below the leaf level (depth 16)");
    ++nodes_;
    for (int child = 0; child < 8; ++child) {
      if ((children >> child & 1u) != 0) full_node(depth + 1);
    }
  }

  unsigned byte() {
    if (pos_ == file_.data.size()) throw DataEnds{};
    return static_cast<unsigned char>(file_.data[pos_++]);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ": malformed OctoMap tree: " + what + " at byte " +
                std::to_string(file_.data_offset + pos_) + " of the file");
  }

  const std::string& path_;
  const OctomapFile& file_;
  std::size_t pos_ = 0;
  std::uint64_t nodes_ = 0;
};

}  // namespace

void check_octomap_data(const std::string& path, const OctomapFile& file) {
  DataWalker walker(path, file);
  const std::string header_size = "the header's size is " + std::to_string(file.size) + " nodes";
  std::uint64_t nodes = 0;
  try {
    nodes = walker.walk();
  } catch (const DataEnds&) {
    throw Error(path + ": truncated OctoMap tree: " + header_size + ", the data ends after " +
                std::to_string(walker.nodes()) + " (at byte " +
                std::to_string(file.data_offset + file.data.size()) + " of the file)");
  }
  if (nodes != file.size) {
    throw Error(path + ": OctoMap tree size mismatch: " + header_size + ", the data holds " +
                std::to_string(nodes));
  }
  if (walker.end() != file.data.size()) {
    const std::size_t extra = file.data.size() - walker.end();
    throw Error(path + ": " + std::to_string(extra) +
                (extra == 1 ? " byte follows" : " bytes follow") +
                " the end of the OctoMap tree (its " + std::to_string(nodes) +
                " nodes end at byte " + std::to_string(file.data_offset + walker.end()) + " of " +
                std::to_string(file.data_offset + file.data.size()) + ")");
  }
}

}  // namespace gridloc::octomap_detail
