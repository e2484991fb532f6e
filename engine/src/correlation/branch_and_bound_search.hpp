#pragma once
// The branch-and-bound search itself (branch_and_bound.cpp's public functions run it): the
// best-first heaps, the depth-first descent below them, the shared incumbent and the
// budgets. Private to the engine's correlation sources.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <tuple>
#include <vector>

#include "gridloc/engine/correlation/branch_and_bound.hpp"
#include "interval_bound.hpp"

// Exactness rests on IEEE rounding being monotone and on the bound being summed exactly as
// score() sums (see block_bound); reassociating compilers would break both.
#if defined(__FAST_MATH__)
#error "branch and bound needs IEEE floating point: build without -ffast-math"
#endif

namespace gridloc::correlation_detail {

inline bool index_less(int it, int iy, int ix, const LatticePose& b) {
  return std::tie(it, iy, ix) < std::tie(b.it, b.iy, b.ix);
}

/// Blocks of at most 2^this cells a side, and at least kBestFirstLevels levels below the
/// top, are searched depth first below the node taken from the heap. Measured on intel's
/// held-out global scans: 1.3-2.5x faster than best first all the way down for about as
/// many cells bounded (depth first from higher up bounded up to 2x more cells); on the
/// apartment's small windows (top level 5) depth first from the top was 1.7x slower, so
/// the levels near the top stay best first.
inline constexpr int kDepthFirstLevel = 5;
inline constexpr int kBestFirstLevels = 5;

/// One branch-and-bound search: per-thread best-first heaps, the shared incumbent, the bounds.
class BranchAndBoundSearch {
 public:
  BranchAndBoundSearch(const Lattice& lattice, const HeadingGrids& grids,
                       const BoundPyramid& pyramid, const BranchAndBoundOptions& options)
      : lattice_(lattice),
        grids_(grids),
        pyramid_(pyramid),
        options_(options),
        global_(*grids.level().global) {
    if (options.heading_intervals && grids.points() != nullptr) {
      intervals_.emplace(lattice, grids, pyramid);
    }
    if (options_.incumbent) {
      best_ = *options_.incumbent;
      found_ = true;
      best_score_.store(best_.score);
    }
    // Leaves below the floor never become the incumbent; nodes bounded below it are dropped.
    if (options_.min_score > best_score_.load()) best_score_.store(options_.min_score);
    if (options_.budget_ms > 0.0) {
      deadline_ = std::chrono::steady_clock::now() +
                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double, std::milli>(options_.budget_ms));
    }
  }

  /// The whole search on options.threads threads (search_branch_and_bound).
  SearchResult run();

  /// A search run a budget at a time, on one thread: its top nodes (or, with no bound
  /// levels, the whole exhaustive search; then it is over at once).
  void begin();

  /// Runs until about `cells` more cells were read or the search is over; true when over.
  bool advance(long long cells);
  bool over() const { return over_; }
  /// The result once over() (moved out).
  SearchResult take_result() { return std::move(result_); }

  /// The share of the lattice's poses still in open nodes that could hold a candidate.
  double open_share() const;

 private:
  /// A block of 2^block_level x 2^block_level translations starting at cell (x, y), times the
  /// 2^heading_level headings starting at `heading` (clipped to the lattice). Its first pose
  /// in lattice order is (heading, y, x): every other pose has a larger heading, or row, or
  /// the same row and a larger column.
  struct Node {
    double bound = 0.0;
    int heading = 0, y = 0, x = 0, block_level = 0, heading_level = 0;
  };

  /// Visit order: higher bound first, then lower first pose.
  static bool visit_before(const Node& a, const Node& b) {
    if (a.bound != b.bound) return a.bound > b.bound;
    return std::tie(a.heading, a.y, a.x) < std::tie(b.heading, b.y, b.x);
  }
  static bool heap_less(const Node& a, const Node& b) { return visit_before(b, a); }

  /// What one thread collects before merging it under the lock.
  struct Worker {
    explicit Worker(BranchAndBoundSearch& s) : search(s) {}
    BranchAndBoundSearch& search;
    std::vector<Node> children;
    /// descend()'s children, one list per depth (a deque: growing it keeps the references
    /// the shallower calls hold).
    std::deque<std::vector<Node>> levels;
    std::vector<LatticePose> scored;
    long long cells = 0;

    /// Scores the pose (unless excluded) and makes it the incumbent when it is better.
    void score_leaf(int it, int iy, int ix) {
      for (const Exclusion& zone : search.options_.exclude) {
        if (zone.contains(ix, iy, it)) return;
      }
      const PlacedLocalGrid& local = search.grids_.placed(it);
      const LatticePose c{ix, iy, it, score(search.global_, local, ix, iy)};
      cells += static_cast<long long>(local.value.size());
      scored.push_back(c);
      // Lock-free reject of the usual case: strictly worse than the incumbent.
      if (c.score < search.best_score_.load(std::memory_order_relaxed)) return;
      std::lock_guard<std::mutex> lock(search.mutex_);
      if (!search.found_ || better(c, search.best_)) {
        search.best_ = c;
        search.found_ = true;
        search.best_score_.store(c.score, std::memory_order_relaxed);
      }
    }

    /// Bounds (or scores, for a single pose) the child node and keeps it if promising.
    void add_child(int heading, int heading_level, int y, int x, int block_level) {
      const Lattice& lattice = search.lattice_;
      if (heading_level == 0 && block_level == 0) {
        score_leaf(heading, y, x);
        return;
      }
      const int last_heading = std::min(heading + (1 << heading_level) - 1, lattice.headings - 1);
      const int side = 1 << block_level;
      // A node inside one zone holds no candidate (one covered only by several zones
      // together is kept: only less pruning).
      for (const Exclusion& zone : search.options_.exclude) {
        if (zone.contains_block(heading, last_heading, x, y, std::min(x + side - 1, lattice.x1),
                                std::min(y + side - 1, lattice.y1))) {
          return;
        }
      }
      Node node{0.0, heading, y, x, block_level, heading_level};
      if (heading_level == 0) {
        const PlacedLocalGrid& local = search.grids_.placed(heading);
        node.bound = block_bound(search.pyramid_, local, block_level, x, y);
        cells += static_cast<long long>(local.value.size());
      } else {
        node.bound = search.intervals_->bound(heading, last_heading, x, y, block_level);
        cells += static_cast<long long>(search.intervals_->point_count());
      }
      if (search.promising_fast(node)) children.push_back(node);
    }

    /// Adds the node's children: its two half intervals of headings while their widening is
    /// at least half the block, else its four sub-blocks.
    void expand(const Node& node) {
      const Lattice& lattice = search.lattice_;
      if (node.heading_level > 0 &&
          (node.block_level == 0 ||
           2 * search.intervals_->widening(search.intervals_->max_norm(),
                                           IntervalBound::half_span(node.heading_level)) >=
               (1 << node.block_level))) {
        const int half = 1 << (node.heading_level - 1);
        add_child(node.heading, node.heading_level - 1, node.y, node.x, node.block_level);
        if (node.heading + half < lattice.headings) {
          add_child(node.heading + half, node.heading_level - 1, node.y, node.x, node.block_level);
        }
        return;
      }
      const int half = 1 << (node.block_level - 1);
      const int x_end = std::min(node.x + 2 * half - 1, lattice.x1);
      const int y_end = std::min(node.y + 2 * half - 1, lattice.y1);
      for (int iy = node.y; iy <= y_end; iy += half) {
        for (int ix = node.x; ix <= x_end; ix += half) {
          add_child(node.heading, node.heading_level, iy, ix, node.block_level - 1);
        }
      }
    }

    /// Hands the scored leaves and counters to the search (under its lock).
    void merge() {
      std::lock_guard<std::mutex> lock(search.mutex_);
      search.result_.poses_scored += static_cast<long long>(scored.size());
      search.result_.cells_scored += cells;
      search.result_.scored.insert(search.result_.scored.end(), scored.begin(), scored.end());
      scored.clear();
      cells = 0;
    }
  };

  /// No bound levels: every pose scored, in lattice order.
  SearchResult run_exhaustive();

  /// The heading level of the top nodes: with heading intervals, the widest interval whose
  /// widening stays within half a top block; 0 (one heading per node) otherwise.
  int top_heading_level(int top) const {
    int level = 0;
    if (intervals_) {
      while (
          (1 << level) < lattice_.headings &&
          2 * intervals_->widening(intervals_->max_norm(), IntervalBound::half_span(level + 1)) <=
              (1 << top)) {
        ++level;
      }
    }
    return level;
  }

  /// The level of the top nodes' blocks (and the depth-first level below it): on a lattice
  /// 17 cells or more across, one below the level whose one block covers it. Such a block's
  /// bound reached the best score at every heading of the apartment's windows (81-167
  /// bounds pruning nothing): starting from 4 blocks a heading was 8-11 % faster there, the
  /// same on the whole map (bench/RESULTS.md). A smaller lattice keeps its one block.
  int top_level() {
    const int whole = bound_depth_for(lattice_);
    const int top = std::min(pyramid_.depth(), whole >= 5 ? whole - 1 : whole);
    depth_first_level_ = std::min(kDepthFirstLevel, top - kBestFirstLevels);
    return top;
  }

  /// The lattice poses a node holds.
  double poses_in(const Node& node) const {
    const int side = 1 << node.block_level;
    const int last = std::min(node.heading + (1 << node.heading_level), lattice_.headings);
    return double(std::min(node.x + side, lattice_.x1 + 1) - node.x) *
           double(std::min(node.y + side, lattice_.y1 + 1) - node.y) * double(last - node.heading);
  }

  /// Thread t's top nodes (every threads-th interval of 2^heading_level headings, blocks of
  /// 2^top cells) into heap t; an error stops the search.
  void make_top_nodes(std::size_t t, std::size_t threads, int top, int heading_level);

  /// What becomes of a node: expanded, set aside (set_aside) or dropped.
  enum class Fate { Expand, SetAside, Drop };

  /// Should the node be expanded: could it hold a pose better than the incumbent, or one
  /// within keep_share of it (unless set_aside takes it)? Reads the incumbent's score
  /// without the lock first: it only ever rises, so a stale value never drops a node that
  /// could win; only a bound equal to it needs the exact test.
  Fate fate_of(const Node& node) {
    const double incumbent = best_score_.load(std::memory_order_relaxed);
    if (node.bound > incumbent) return Fate::Expand;
    if (node.bound == incumbent) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (could_win(node)) return Fate::Expand;
    }
    if (!keeps(node, incumbent)) return Fate::Drop;
    return set_aside(node) ? Fate::SetAside : Fate::Expand;
  }
  bool promising_fast(const Node& node) { return fate_of(node) == Fate::Expand; }
  /// Exact test, under the lock.
  bool promising(const Node& node) const {
    return could_win(node) || (found_ && keeps(node, best_.score));
  }
  /// Whether the node could hold a pose better than the incumbent (or reach min_score while
  /// there is none). An equal score wins only at a lower index, and the node's lowest index
  /// is its first pose.
  bool could_win(const Node& node) const {
    if (node.bound < options_.min_score) return false;
    if (!found_) return true;
    if (node.bound != best_.score) return node.bound > best_.score;
    return index_less(node.heading, node.y, node.x, best_);
  }
  /// Whether keep_share asks for the node: its bound reaches that share of `incumbent`.
  bool keeps(const Node& node, double incumbent) const {
    return options_.keep_share < 1.0 && incumbent > 0.0 &&
           node.bound >= options_.keep_share * incumbent;
  }
  /// A node kept only by keep_share that lies wholly within keep_outside's neighbourhood of
  /// the incumbent: kept for search_set_aside() (dropped once the best is final).
  bool set_aside(const Node& node) {
    if (!options_.keep_outside) return false;
    std::lock_guard<std::mutex> lock(mutex_);
    if (!found_ || !within_best_neighbourhood(node)) return false;
    if (!best_is_final_) set_aside_.push_back(node);
    return true;
  }
  /// Whether every pose of the node lies in keep_outside's neighbourhood of the incumbent.
  bool within_best_neighbourhood(const Node& node) const {
    Exclusion zone = *options_.keep_outside;
    zone.center = best_;
    const int last_heading =
        std::min(node.heading + (1 << node.heading_level) - 1, lattice_.headings - 1);
    const int side = 1 << node.block_level;
    return zone.contains_block(node.heading, last_heading, node.x, node.y,
                               std::min(node.x + side - 1, lattice_.x1),
                               std::min(node.y + side - 1, lattice_.y1));
  }
  /// Once the search is over (the best is final): searches the nodes set aside that do not
  /// lie wholly within the best pose's neighbourhood, on thread 0.
  void search_set_aside();

  /// Expands `node`: the children of a block above depth_first_level_ go to heap t (best
  /// first over the whole search); those of a smaller one are visited at once, best first,
  /// depth first (Cartographer's order: no heap to keep for the many small nodes). When the
  /// search stops, the children not yet visited go back to heap t, so that finish() sees
  /// every open node.
  void descend(std::size_t t, const Node& node, Worker& worker, std::size_t depth) {
    if (worker.levels.size() <= depth) worker.levels.resize(depth + 1);
    worker.children.clear();
    worker.expand(node);
    std::vector<Node>& children = worker.levels[depth];
    children.swap(worker.children);
    if (node.block_level > depth_first_level_) {  // coarse: back to the heap, best first
      std::lock_guard<std::mutex> lock(*heap_mutex_[t]);
      for (const Node& child : children) {
        heaps_[t].push_back(child);
        std::push_heap(heaps_[t].begin(), heaps_[t].end(), heap_less);
      }
      return;
    }
    std::sort(children.begin(), children.end(), visit_before);
    for (std::size_t k = 0; k < children.size(); ++k) {
      if (out_of_time(worker)) {
        std::lock_guard<std::mutex> lock(*heap_mutex_[t]);
        for (std::size_t rest = k; rest < children.size(); ++rest) {
          heaps_[t].push_back(children[rest]);
          std::push_heap(heaps_[t].begin(), heaps_[t].end(), heap_less);
        }
        return;
      }
      if (promising_fast(children[k])) descend(t, children[k], worker, depth + 1);
    }
  }

  /// Whether the search was stopped, or its budget (time, or the cells `worker` may read
  /// in this run) just ran out (then it stops).
  bool out_of_time(const Worker& worker) {
    if (stopped_.load(std::memory_order_relaxed)) return true;
    if (cells_allowance_ >= 0 && worker.cells >= cells_allowance_) {
      stopped_ = true;
      return true;
    }
    if (!deadline_ || std::chrono::steady_clock::now() < *deadline_) return false;
    stopped_ = true;
    return true;
  }

  /// Takes the best promising node of thread t's heap, or else steals one from another
  /// heap (so a thread whose share ran out helps the others). Counts it as in work.
  bool take(std::size_t t, Node& node) {
    for (std::size_t i = 0; i < heaps_.size(); ++i) {
      const std::size_t v = (t + i) % heaps_.size();
      std::lock_guard<std::mutex> lock(*heap_mutex_[v]);
      std::vector<Node>& heap = heaps_[v];
      while (!heap.empty()) {
        const Fate fate = fate_of(heap.front());
        if (fate == Fate::Drop) break;  // none after it bounds more
        std::pop_heap(heap.begin(), heap.end(), heap_less);
        node = heap.back();
        heap.pop_back();
        if (fate == Fate::SetAside) continue;
        ++active_;
        return true;
      }
    }
    return false;
  }

  /// Thread t's loop: take a node, expand it, keep its promising children in heap t. A thread
  /// stops when no heap holds a promising node and no node is being expanded (a thread that
  /// pushes children always looks again, so no node is left behind).
  void work(std::size_t t) {
    Worker worker(*this);
    try {
      while (!out_of_time(worker)) {
        Node node;
        if (!take(t, node)) {
          if (active_.load() == 0) break;
          std::this_thread::yield();
          continue;
        }
        descend(t, node, worker, 0);
        --active_;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      stopped_ = true;
    }
    worker.merge();
  }

  /// The result once the threads stopped: the incumbent, and whether an open node could
  /// still beat it (then not proven optimal, and the highest such bound).
  SearchResult finish(bool stopped);

  /// Out of time before any pose was scored: dives from the best open node to a leaf.
  void dive(const std::vector<Node>& open);

  const Lattice& lattice_;
  const HeadingGrids& grids_;
  const BoundPyramid& pyramid_;
  const BranchAndBoundOptions& options_;
  const PaddedGrid& global_;  ///< the searched level's padded grid
  /// The bounds of nodes of several headings (BranchAndBoundOptions::heading_intervals).
  std::optional<IntervalBound> intervals_;
  int depth_first_level_ = kDepthFirstLevel;  ///< blocks at or below it: depth first
  std::optional<std::chrono::steady_clock::time_point> deadline_;

  std::vector<std::vector<Node>> heaps_;                 ///< one best-first heap per thread ...
  std::vector<std::unique_ptr<std::mutex>> heap_mutex_;  ///< ... each with its lock
  std::atomic<int> active_{0};                           ///< nodes being expanded
  std::atomic<int> roots_pending_{0};                    ///< threads still making top nodes

  mutable std::mutex mutex_;  // guards the incumbent, the error, the result, set_aside_
  LatticePose best_;
  bool found_ = false;
  std::vector<Node> set_aside_;  ///< see set_aside()
  bool best_is_final_ = false;   ///< search_set_aside() runs: set-aside nodes are dropped
  std::atomic<double> best_score_{-std::numeric_limits<double>::infinity()};
  std::atomic<bool> stopped_{false};
  std::exception_ptr error_;
  SearchResult result_;
  /// A search run a budget at a time: the cells one run may read (-1: no limit), and
  /// whether it is over (result_ then holds the result).
  long long cells_allowance_ = -1;
  bool over_ = false;
};

}  // namespace gridloc::correlation_detail
