// Tests of grids/src/octomap_file.cpp and octomap_check.cpp: OctoMap files checked whole
// before octomap reads them (truncated, mis-sized, malformed and trailing data, header faults,
// directories, limits), nothing printed on stderr, and concurrent loads.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "gridloc/grids/octomap_io.hpp"
#ifdef GRIDLOC_CLI_PATH
#include "cli_support.hpp"
#endif
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::TempDir;

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The message of the gridloc::Error `fn` throws, or a note saying it threw none.
template <typename Fn>
std::string message_of(Fn fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("another exception: ") + e.what();
  }
  return "no error";
}

std::string load_error(const std::string& path, const OctomapSlice& slice = {}) {
  return message_of([&] { load_octomap(path, slice); });
}

/// Where the node data starts: after the header's "data\n" line.
std::size_t data_offset(const std::string& file) {
  return file.find("\ndata\n") + 6;
}

/// A 51-node tree (five voxels at z 0.3-0.4 m, in three of the root's octants, two of them
/// with a sibling), not pruned: its .ot is 385 bytes.
octomap::OcTree small_tree() {
  octomap::OcTree tree(0.1);
  const float xy[5][2] = {
      {0.05f, 0.05f}, {0.15f, 0.05f}, {-0.05f, 0.05f}, {-0.15f, 0.05f}, {0.05f, -0.05f}};
  for (int i = 0; i < 5; ++i) tree.updateNode(octomap::point3d(xy[i][0], xy[i][1], 0.35f), i != 1);
  return tree;
}

/// A tree of a few thousand nodes: random occupied and free voxels in a 3 m x 3 m x 0.8 m box.
octomap::OcTree random_tree() {
  octomap::OcTree tree(0.1);
  std::mt19937 rng(14);
  std::uniform_int_distribution<int> xy(-15, 14), z(0, 7), coin(0, 3);
  for (int i = 0; i < 3000; ++i) {
    tree.updateNode(
        octomap::point3d((xy(rng) + 0.5f) * 0.1f, (xy(rng) + 0.5f) * 0.1f, (z(rng) + 0.5f) * 0.1f),
        coin(rng) == 0);
  }
  return tree;
}

std::string header(bool binary, const std::string& size, const std::string& res = "0.1") {
  return std::string(binary ? "# Octomap OcTree binary file" : "# Octomap OcTree file") +
         "\nid OcTree\nsize " + size + "\nres " + res + "\ndata\n";
}

/// A hand-made .bt data: the chain of inner nodes from the root to one occupied leaf at
/// x [0, 0.1) y [0, 0.1) z [0.3, 0.4) m (key 32768, 32768, 32771), 17 nodes. Per inner node
/// two bytes of 2-bit child codes (3: inner child, 2: occupied leaf), child index x + 2y + 4z
/// of the key's bit at that depth.
std::string chain_to_one_voxel() {
  std::string data("\x00\xC0", 2);  // root: child 7 (bit 15: 1, 1, 1)
  for (int d = 1; d <= 13; ++d) data += std::string("\x03\x00", 2);  // bits 14-2: child 0
  data += std::string("\x00\x03", 2);                                // bit 1: child 4 (z only)
  data += std::string("\x00\x02", 2);  // bit 0: child 4, occupied leaf
  return data;
}

class OctomapCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    octomap::OcTree tree = small_tree();
    ot_ = dir_.file("small.ot");
    ASSERT_TRUE(tree.write(ot_));  // before writeBinary, which prunes
    bt_ = dir_.file("small.bt");
    ASSERT_TRUE(tree.writeBinary(bt_));
  }

  /// `bytes` written to `name` in the test's folder.
  std::string write(const std::string& name, const std::string& bytes) const {
    return dir_.write(name, bytes);
  }
  /// The first `n` bytes of `path` written to `name`.
  std::string cut(const std::string& path, std::size_t n, const std::string& name) const {
    return write(name, contents(path).substr(0, n));
  }

  TempDir dir_;
  std::string ot_, bt_;
};

TEST_F(OctomapCheck, TruncatedFullTreeIsRefused) {
  const std::string whole = contents(ot_);
  ASSERT_EQ(whole.size(), 385u);
  ASSERT_EQ(data_offset(whole), 130u);  // 51 nodes of 5 bytes follow
  const std::string c = cut(ot_, 250, "cut.ot");
  EXPECT_EQ(load_error(c), c + ": truncated OctoMap tree: the header's size is 51 nodes, the data "
                               "ends after 24 (at byte 250 of the file)");
  // Every cut inside the data is refused so.
  for (std::size_t n = 130; n < whole.size(); ++n) {
    const std::string each = cut(ot_, n, "each" + std::to_string(n) + ".ot");
    EXPECT_NE(load_error(each).find("truncated OctoMap tree"), std::string::npos) << n;
  }
}

TEST_F(OctomapCheck, TruncatedBinaryTreeIsRefused) {
  const std::string whole = contents(bt_);
  const std::size_t start = data_offset(whole);
  const std::string c = cut(bt_, start + (whole.size() - start) / 2, "cut.bt");
  EXPECT_EQ(load_error(c).rfind(c + ": truncated OctoMap tree: the header's size is ", 0), 0u)
      << load_error(c);
  for (std::size_t n = start; n < whole.size(); ++n) {
    const std::string each = cut(bt_, n, "each" + std::to_string(n) + ".bt");
    EXPECT_NE(load_error(each).find("truncated OctoMap tree"), std::string::npos) << n;
  }
}

TEST_F(OctomapCheck, LargerTreeCutToATenthIsRefused) {
  octomap::OcTree tree = random_tree();
  const std::string ot = dir_.file("random.ot"), bt = dir_.file("random.bt");
  ASSERT_TRUE(tree.write(ot));
  const std::string nodes = std::to_string(tree.size());
  ASSERT_GT(tree.size(), 3000u);
  ASSERT_TRUE(tree.writeBinary(bt));
  const std::string bt_nodes = std::to_string(tree.size());
  EXPECT_EQ(load_error(ot), "no error");
  EXPECT_EQ(load_error(bt), "no error");

  const std::size_t tenth = contents(ot).size() / 10;
  const std::string c = cut(ot, tenth, "tenth.ot");
  const std::size_t whole_nodes = (tenth - data_offset(contents(ot))) / 5;
  EXPECT_EQ(load_error(c), c + ": truncated OctoMap tree: the header's size is " + nodes +
                               " nodes, the data ends after " + std::to_string(whole_nodes) +
                               " (at byte " + std::to_string(tenth) + " of the file)");
  const std::string cb = cut(bt, contents(bt).size() / 10, "tenth.bt");
  EXPECT_EQ(load_error(cb).rfind(cb + ": truncated OctoMap tree: the header's size is " + bt_nodes +
                                     " nodes, the data ends after ",
                                 0),
            0u)
      << load_error(cb);
}

// A real tree nobody here produced, as .bt and converted to .ot, cut to a tenth (before the
// checks a cut .ot loaded as a tree of a few voxels: "4.29497e+09 cells").
TEST_F(OctomapCheck, RealTreeCutToATenthIsRefused) {
  const std::string path =
      std::string(GRIDLOC_TEST_SHARED_DIR) + "/datasets/OctoMap_octomap/geb079.bt";
  if (!std::filesystem::exists(path)) {
    GTEST_SKIP() << "../shared is absent (" << path << "): real-tree test skipped";
  }
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(path));
  ASSERT_EQ(tree.size(), 532566u);
  const std::string ot = dir_.file("geb079.ot");
  ASSERT_TRUE(tree.write(ot));
  const std::string cut_ot = cut(ot, contents(ot).size() / 10, "geb079_tenth.ot");
  EXPECT_EQ(load_error(cut_ot),
            cut_ot +
                ": truncated OctoMap tree: the header's size is 532566 "
                "nodes, the data ends after 53232 (at byte 266296 of the file)");
  const std::string cut_bt = cut(path, contents(path).size() / 10, "geb079_tenth.bt");
  EXPECT_EQ(load_error(cut_bt).rfind(
                cut_bt + ": truncated OctoMap tree: the header's size is 532566 nodes, the data "
                         "ends after ",
                0),
            0u)
      << load_error(cut_bt);
}

TEST_F(OctomapCheck, SizeMismatchIsRefused) {
  std::string text = contents(ot_);
  const std::size_t at = text.find("size 51\n");
  ASSERT_NE(at, std::string::npos);
  const std::string more = write("more.ot", std::string(text).replace(at, 7, "size 52"));
  EXPECT_EQ(load_error(more), more +
                                  ": OctoMap tree size mismatch: the header's size is 52 "
                                  "nodes, the data holds 51");
  const std::string fewer = write("fewer.ot", std::string(text).replace(at, 7, "size 9"));
  EXPECT_EQ(load_error(fewer), fewer +
                                   ": OctoMap tree size mismatch: the header's size is 9 "
                                   "nodes, the data holds 51");
  // A .bt too, and a size of 0 with data after it.
  const std::string chain = chain_to_one_voxel();
  const std::string bt = write("chain18.bt", header(true, "18") + chain);
  EXPECT_EQ(load_error(bt), bt + ": OctoMap tree size mismatch: the header's size is 18 nodes, "
                                 "the data holds 17");
  const std::string zero = write("zero.bt", header(true, "0") + chain);
  EXPECT_EQ(load_error(zero), zero +
                                  ": OctoMap tree size mismatch: the header's size is 0 nodes, "
                                  "the data holds 17");
}

TEST_F(OctomapCheck, BytesAfterTheTreeAreRefused) {
  const std::string extra = write("extra.ot", contents(ot_) + "abc");
  EXPECT_EQ(load_error(extra), extra +
                                   ": 3 bytes follow the end of the OctoMap tree (its 51 nodes "
                                   "end at byte 385 of 388)");
  const std::string one = write("one.bt", header(true, "17") + chain_to_one_voxel() + "\n");
  EXPECT_EQ(load_error(one), one +
                                 ": 1 byte follows the end of the OctoMap tree (its 17 nodes end "
                                 "at byte 92 of 93)");
}

TEST_F(OctomapCheck, HandMadeChainIsOctomapsOwnBytes) {
  octomap::OcTree tree(0.1);
  tree.updateNode(octomap::point3d(0.05f, 0.05f, 0.35f), true);
  std::ostringstream out;
  ASSERT_TRUE(tree.writeBinary(out));
  EXPECT_EQ(out.str().substr(data_offset(out.str())), chain_to_one_voxel());
  const std::string bt = write("chain.bt", header(true, "17") + chain_to_one_voxel());
  const OccupancyMap m = load_octomap(bt);
  ASSERT_EQ(m.width(), 1);
  ASSERT_EQ(m.height(), 1);
  EXPECT_EQ(m.at(0, 0), CellState::Occupied);
  EXPECT_NEAR(m.geometry.origin.x(), 0.0, 1e-9);
  EXPECT_NEAR(m.geometry.origin.y(), 0.0, 1e-9);
}

TEST_F(OctomapCheck, MalformedNodeDataIsRefused) {
  // A chain one level too deep: the depth-15 node has an inner child.
  std::string deep = chain_to_one_voxel();
  deep.replace(deep.size() - 2, 2, std::string("\x00\x03", 2));
  const std::string too_deep = write("deep.bt", header(true, "17") + deep + std::string(2, '\0'));
  EXPECT_EQ(load_error(too_deep), too_deep +
                                      ": malformed OctoMap tree: a node below the leaf "
                                      "level (depth 16) at byte 92 of the file");
  // An inner node whose codes name no child.
  const std::string childless =
      write("childless.bt", header(true, "2") + std::string("\x03\x00\x00\x00", 4));
  EXPECT_EQ(load_error(childless), childless +
                                       ": malformed OctoMap tree: an inner node without "
                                       "children at byte 63 of the file");
  // A .ot node whose log-odds is NaN.
  std::string text = contents(ot_);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(text.data() + data_offset(text) + 5, &nan, sizeof nan);  // the second node
  const std::string bad_value = write("nan.ot", text);
  EXPECT_EQ(load_error(bad_value), bad_value +
                                       ": malformed OctoMap tree: a node whose log-odds "
                                       "is not finite at byte 139 of the file");
  // A .ot chain of 18 nodes, each the only child of the one before: below the leaf level.
  std::string chain;
  for (int d = 0; d <= 17; ++d)
    chain += std::string(4, '\0') + (d < 17 ? "\x01" : std::string(1, '\0'));
  const std::string deep_ot = write("deep.ot", header(false, "18") + chain);
  EXPECT_EQ(load_error(deep_ot), deep_ot +
                                     ": malformed OctoMap tree: a node below the leaf level "
                                     "(depth 16) at byte 138 of the file");
}

TEST_F(OctomapCheck, DirectoryIsRefused) {
  const std::string folder = dir_.file("folder.bt");
  std::filesystem::create_directory(folder);
  EXPECT_EQ(load_error(folder), folder + ": is a directory, not a binary OctoMap (.bt)");
  const std::string folder_ot = dir_.file("folder.ot");
  std::filesystem::create_directory(folder_ot);
  EXPECT_EQ(load_error(folder_ot), folder_ot + ": is a directory, not a full OctoMap (.ot)");
}

TEST_F(OctomapCheck, HeaderFaultsAreRefused) {
  const std::string chain = chain_to_one_voxel();
  const std::string first = "# Octomap OcTree binary file\n";
  const struct {
    std::string head, message;
  } cases[] = {
      {first + "id OcTree\nsize 17\nres 0.1\ncolor red\ndata\n",
       "unknown keyword 'color' in the OctoMap header (expected id, size, res, data)"},
      {first + "size 17\nres 0.1\ndata\n", "the OctoMap header has no 'id' (the tree type)"},
      {first + "id OcTree\nres 0.1\ndata\n",
       "the OctoMap header has no 'size' (the tree's node count)"},
      {first + "id OcTree\nsize 17\ndata\n", "the OctoMap header has no 'res' (the leaf size)"},
      {first + "id OcTree\nsize 17\nsize 17\nres 0.1\ndata\n",
       "the OctoMap header gives 'size' twice"},
      {first + "id OcTree\nsize -5\nres 0.1\ndata\n",
       "the OctoMap header's size '-5' is not a node count (a whole number below 2^32)"},
      {first + "id OcTree\nsize 17x\nres 0.1\ndata\n",
       "the OctoMap header's size '17x' is not a node count (a whole number below 2^32)"},
      {first + "id OcTree\nsize 4294967296\nres 0.1\ndata\n",
       "the OctoMap header's size '4294967296' is not a node count (a whole number below 2^32)"},
      {first + "id OcTree\nsize 17\nres nan\ndata\n",
       "the OctoMap header's res 'nan' is not a number"},
      {first + "id OcTree\nsize 17\nres 0.1m\ndata\n",
       "the OctoMap header's res '0.1m' is not a number"},
      {first + "id OcTree\nsize 17\nres 0\ndata\n",
       "the OctoMap header's res 0 is not a leaf size from 1e-6 to 1e6 m"},
      {first + "id OcTree\nsize 17\nres -0.1\ndata\n",
       "the OctoMap header's res -0.1 is not a leaf size from 1e-6 to 1e6 m"},
      {first + "id OcTree\nsize 17\nres 1e300\ndata\n",
       "the OctoMap header's res 1e300 is not a leaf size from 1e-6 to 1e6 m"},
      {first + "id OcTree\nsize 17\nres 0.1\ndata junk\n",
       "the OctoMap header's 'data' line holds more than 'data'"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string path = write("case" + std::to_string(i++) + ".bt", c.head + chain);
    EXPECT_EQ(load_error(path), path + ": " + c.message);
  }
  const std::string no_data = write("no_data.bt", first + "id OcTree\nsize 17\nres 0.1\n");
  EXPECT_EQ(load_error(no_data), no_data + ": the OctoMap header ends without a 'data' line");
  const std::string no_value = write("no_value.bt", first + "id OcTree\nsize");
  EXPECT_EQ(load_error(no_value),
            no_value + ": the OctoMap header ends before the value of 'size'");
  const std::string unprintable = write("binary.bt", first + "id OcTree\n" + chain);
  EXPECT_EQ(load_error(unprintable).rfind(unprintable + ": unknown keyword '??", 0), 0u)
      << load_error(unprintable);
}

TEST_F(OctomapCheck, HeaderVariantsOctomapWritesOrAcceptsLoadAlike) {
  const OccupancyMap want = load_octomap(ot_);
  std::string text = contents(ot_);
  // Comment lines anywhere, keywords in another order, octomap's deprecated id "1".
  std::string other = "# Octomap OcTree file\n# a note\nres 0.1\n#\nsize 51\nid 1\n  data  \n" +
                      text.substr(data_offset(text));
  const std::string path = write("variant.ot", other);
  EXPECT_EQ(load_octomap(path).cells, want.cells);
  // A .bt's id does not matter: its data is occupancy codes whatever the tree type.
  const std::string color = write("color.bt",
                                  "# Octomap OcTree binary file\nid ColorOcTree\nsize "
                                  "17\nres 0.1\ndata\n" +
                                      chain_to_one_voxel());
  EXPECT_EQ(load_octomap(color).at(0, 0), CellState::Occupied);
}

TEST_F(OctomapCheck, LimitsAreChecked) {
  // The tree's memory, estimated from the header's size before octomap allocates it: 48 bytes
  // a node, and the file's bytes.
  ResourceLimits limits;
  limits.max_memory_mb = 1.0;
  const std::string huge = write("huge.bt", header(true, "4000000000") + chain_to_one_voxel());
  EXPECT_EQ(message_of([&] { load_octomap(huge, {}, limits); }),
            huge +
                ": the OctoMap tree of 4000000000 nodes would need about 183106 MB, more than "
                "the limit of 1 MB (raise it with --max-memory-mb)");
  EXPECT_EQ(message_of([&] { load_octomap(ot_, {}, limits); }), "no error");
  // The file's size.
  limits = {};
  limits.max_file_mb = 1.0;
  const std::string big = write("big.bt", std::string((1 << 20) + 1, '#'));
  EXPECT_EQ(message_of([&] { load_octomap(big, {}, limits); }),
            big +
                ": the binary OctoMap (.bt) is 2 MB, more than the limit of 1 MB (raise it with "
                "--max-file-mb)");
  // The 2-D map's cells.
  limits = {};
  limits.max_cells = 1.0;
  EXPECT_EQ(message_of([&] { load_octomap(ot_, {}, limits); }),
            ot_ +
                ": the OctoMap's 2-D map at 0.1 m (4 x 2): 8 cells exceeds the limit of 1 cells "
                "(raise it with --max-cells)");
  // The limits themselves.
  limits.max_cells = 0.0;
  EXPECT_EQ(message_of([&] { load_octomap(ot_, {}, limits); }),
            "resource limits: max_cells must be positive and finite, got 0");
}

// octomap's readers print their warnings and errors on stderr (std::cerr and fprintf); the
// checks keep every bad file from them, and the loader leaves std::cerr alone.
TEST_F(OctomapCheck, NothingIsPrinted) {
  const std::string whole = contents(bt_);
  const std::vector<std::string> files = {
      ot_,
      bt_,
      cut(bt_, whole.size() - 3, "cut.bt"),
      cut(ot_, 250, "cut.ot"),
      write("junk.bt", header(true, "17") + "junk junk junk"),
      write("keyword.bt", "# Octomap OcTree binary file\nfoo 1\n"),
      write("color.ot", "# Octomap OcTree file\nid ColorOcTree\nsize 1\nres 0.1\ndata\n"),
  };
  std::streambuf* const before = std::cerr.rdbuf();
  ::testing::internal::CaptureStderr();
  for (const std::string& f : files) message_of([&] { load_octomap(f); });
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed, "");
  EXPECT_EQ(std::cerr.rdbuf(), before);
}

bool same_map(const OccupancyMap& a, const OccupancyMap& b) {
  return a.cells == b.cells && a.width() == b.width() && a.height() == b.height() &&
         a.geometry.origin == b.geometry.origin && a.geometry.resolution == b.geometry.resolution;
}

// 4 threads x 200 loads of good and bad files, mixed: each gives its map or its error, as one
// load alone does, and std::cerr keeps its buffer (the loader once swapped it, unlocked).
TEST_F(OctomapCheck, ConcurrentLoadsGiveTheirMapsAndErrors) {
  octomap::OcTree tree = random_tree();
  const std::string big_ot = dir_.file("random.ot"), big_bt = dir_.file("random.bt");
  ASSERT_TRUE(tree.write(big_ot));
  ASSERT_TRUE(tree.writeBinary(big_bt));
  const std::string folder = dir_.file("folder.bt");
  std::filesystem::create_directory(folder);
  const std::vector<std::string> files = {big_ot,
                                          big_bt,
                                          ot_,
                                          cut(big_bt, contents(big_bt).size() / 2, "half.bt"),
                                          cut(ot_, 250, "cut.ot"),
                                          folder};
  std::vector<OccupancyMap> maps;
  std::vector<std::string> errors;
  for (const std::string& f : files) {
    errors.push_back(load_error(f));
    maps.push_back(errors.back() == "no error" ? load_octomap(f) : OccupancyMap());
  }
  ASSERT_EQ(std::count(errors.begin(), errors.end(), "no error"), 3);
  std::streambuf* const before = std::cerr.rdbuf();
  std::atomic<int> wrong{0}, done{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 200; ++i) {
        const std::size_t k = static_cast<std::size_t>(t + i) % files.size();
        if (errors[k] == "no error") {
          try {
            wrong += !same_map(load_octomap(files[k]), maps[k]);
          } catch (...) {
            ++wrong;
          }
        } else {
          wrong += load_error(files[k]) != errors[k];
        }
        ++done;
      }
    });
  }
  for (std::thread& th : threads) th.join();
  EXPECT_EQ(done.load(), 800);
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_EQ(std::cerr.rdbuf(), before);
}

#ifdef GRIDLOC_CLI_PATH

// The tool on a truncated tree: its one error line and nothing of octomap's (which printed
// "ERROR: Tree size mismatch ..." first).
TEST(OctomapCheckCli, TruncatedTreeIsOneErrorLine) {
  TempDir dir;
  octomap::OcTree tree = random_tree();
  const std::string bt = dir.file("random.bt"), ot = dir.file("random.ot");
  ASSERT_TRUE(tree.write(ot));
  ASSERT_TRUE(tree.writeBinary(bt));
  const std::string readings =
      dir.write("r.json", nlohmann::json{{"ranges_m", std::vector<double>(14, 1.0)}}.dump());
  for (const std::string& whole : {bt, ot}) {
    const std::string bytes = contents(whole);
    const std::string cut =
        dir.write("cut" + whole.substr(whole.size() - 3), bytes.substr(0, bytes.size() * 2 / 3));
    const test::CliRun run =
        test::run_cli(dir, "localize --map " + test::quote(cut) + " --readings " +
                               test::quote(readings) + " --prior 0.1,0.1,0");
    test::expect_cli_error(run, {cut, "truncated OctoMap tree: the header's size is "});
  }
}

#endif  // GRIDLOC_CLI_PATH

}  // namespace
}  // namespace gridloc
