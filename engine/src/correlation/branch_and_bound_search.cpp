// The branch-and-bound search's phases run once per search or per advance: the top nodes,
// the threads, the budgeted runs, the result (branch_and_bound_search.hpp has the rest).
#include <algorithm>
#include <thread>
#include <vector>

#include "branch_and_bound_search.hpp"

namespace gridloc::correlation_detail {

SearchResult BranchAndBoundSearch::run() {
  const int top = top_level();
  if (top == 0 && !intervals_) return run_exhaustive();  // no bound levels
  const int top_headings = top_heading_level(top);
  // Each thread makes the top nodes of its share of the headings (building their grids in
  // parallel) into its own best-first heap, then searches, sharing the incumbent and
  // stealing from the others' heaps when its own runs dry.
  const auto threads = static_cast<std::size_t>(std::max(1, options_.threads));
  heaps_.assign(threads, {});
  for (std::size_t t = 0; t < threads; ++t) heap_mutex_.push_back(std::make_unique<std::mutex>());
  roots_pending_ = static_cast<int>(threads);
  auto run_thread = [this, top, top_headings, threads](std::size_t t) {
    make_top_nodes(t, threads, top, top_headings);
    // Every heap must hold its top nodes before anyone may conclude the search is over.
    --roots_pending_;
    while (roots_pending_.load() > 0) std::this_thread::yield();
    work(t);
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(run_thread, t);
  run_thread(0);
  for (auto& t : pool) t.join();
  if (!error_ && !stopped_.load()) search_set_aside();
  if (error_) std::rethrow_exception(error_);
  return finish(stopped_.load());
}

void BranchAndBoundSearch::search_set_aside() {
  if (!options_.keep_outside || !found_) return;
  best_is_final_ = true;
  std::vector<Node>& heap = heaps_[0];
  for (const Node& node : set_aside_) {
    if (keeps(node, best_.score) && !within_best_neighbourhood(node)) heap.push_back(node);
  }
  set_aside_.clear();
  std::make_heap(heap.begin(), heap.end(), heap_less);
  work(0);
}

void BranchAndBoundSearch::begin() {
  const int top = top_level();
  if (top == 0 && !intervals_) {
    result_ = run_exhaustive();
    over_ = true;
    return;
  }
  heaps_.assign(1, {});
  heap_mutex_.push_back(std::make_unique<std::mutex>());
  make_top_nodes(0, 1, top, top_heading_level(top));
  if (error_) std::rethrow_exception(error_);
}

bool BranchAndBoundSearch::advance(long long cells) {
  if (over_) return true;
  stopped_ = false;
  cells_allowance_ = std::max(1LL, cells);
  work(0);
  if (error_) std::rethrow_exception(error_);
  if (!stopped_.load()) {
    cells_allowance_ = -1;
    search_set_aside();
    if (error_) std::rethrow_exception(error_);
    result_ = finish(false);
    over_ = true;
  }
  return over_;
}

double BranchAndBoundSearch::open_share() const {
  if (over_) return 0.0;
  double open = 0.0;
  for (const auto& heap : heaps_) {
    for (const Node& node : heap) {
      if (promising(node)) open += poses_in(node);
    }
  }
  const double all = double(lattice_.x1 - lattice_.x0 + 1) * double(lattice_.y1 - lattice_.y0 + 1) *
                     double(lattice_.headings);
  return std::min(1.0, open / all);
}

SearchResult BranchAndBoundSearch::run_exhaustive() {
  Worker worker(*this);
  for (int it = 0; it < lattice_.headings; ++it) {
    for (int iy = lattice_.y0; iy <= lattice_.y1; ++iy) {
      for (int ix = lattice_.x0; ix <= lattice_.x1; ++ix) worker.score_leaf(it, iy, ix);
    }
  }
  worker.merge();
  return finish(false);
}

void BranchAndBoundSearch::make_top_nodes(std::size_t t, std::size_t threads, int top,
                                          int heading_level) {
  try {
    Worker worker(*this);
    const int side = 1 << top;
    const int stride = 1 << heading_level;
    for (int it = static_cast<int>(t) * stride; it < lattice_.headings;
         it += static_cast<int>(threads) * stride) {
      for (int iy = lattice_.y0; iy <= lattice_.y1; iy += side) {
        for (int ix = lattice_.x0; ix <= lattice_.x1; ix += side) {
          worker.add_child(it, heading_level, iy, ix, top);
        }
      }
    }
    heaps_[t] = std::move(worker.children);
    std::make_heap(heaps_[t].begin(), heaps_[t].end(), heap_less);
    worker.merge();
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = std::current_exception();
    stopped_ = true;
  }
}

SearchResult BranchAndBoundSearch::finish(bool stopped) {
  // The open nodes that could still win (after the threads stopped: no lock needed).
  std::vector<Node> open;
  for (const auto& heap : heaps_) {
    for (const Node& node : heap) {
      if (could_win(node)) open.push_back(node);
    }
  }
  if (stopped && !found_ && !open.empty()) dive(open);
  result_.best = best_;
  result_.found = found_;
  result_.proven_optimal = true;
  result_.upper_bound = best_.score;
  for (const Node& node : open) {
    if (!could_win(node)) continue;  // (the dive may have raised the incumbent)
    result_.proven_optimal = false;
    result_.upper_bound = std::max(result_.upper_bound, node.bound);
  }
  return std::move(result_);
}

void BranchAndBoundSearch::dive(const std::vector<Node>& open) {
  Worker worker(*this);
  Node node = *std::min_element(open.begin(), open.end(), visit_before);
  while (!found_) {
    worker.expand(node);
    if (found_ || worker.children.empty()) break;
    node = *std::min_element(worker.children.begin(), worker.children.end(), visit_before);
    worker.children.clear();
  }
  worker.merge();
}

}  // namespace gridloc::correlation_detail
