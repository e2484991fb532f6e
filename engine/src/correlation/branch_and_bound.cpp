// Exact branch-and-bound search over a lattice: the best-first search of bounded blocks of
// translations and headings, in parallel, with exclusions, an incumbent and a budget.
#include "gridloc/engine/correlation/branch_and_bound.hpp"

#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include "branch_and_bound_search.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
using correlation_detail::BranchAndBoundSearch;
namespace {

void validate(const Lattice& lattice, const PaddedGrid& g, const BoundPyramid& pyramid) {
  auto fail = [](const std::string& what) { throw Error("branch and bound: " + what); };
  if (lattice.headings < 1) {
    fail("lattice headings = " + std::to_string(lattice.headings) + " must be >= 1");
  }
  if (lattice.x0 < 0 || lattice.x0 > lattice.x1 || lattice.x1 >= g.width || lattice.y0 < 0 ||
      lattice.y0 > lattice.y1 || lattice.y1 >= g.height) {
    std::ostringstream m;
    m << "lattice x [" << lattice.x0 << ", " << lattice.x1 << "] y [" << lattice.y0 << ", "
      << lattice.y1 << "] must be non-empty and inside the " << g.width << " x " << g.height
      << " map";
    fail(m.str());
  }
  if (pyramid.depth() < 0 || pyramid.grid_min.size() != pyramid.arc_max.size() ||
      pyramid.pad != g.pad || pyramid.width != g.width || pyramid.height != g.height) {
    std::ostringstream m;
    m << "the bound pyramid (pad " << pyramid.pad << ", map " << pyramid.width << " x "
      << pyramid.height << ") was not built from the searched grid (pad " << g.pad << ", map "
      << g.width << " x " << g.height << ")";
    fail(m.str());
  }
}

/// validate(), and that the heading grids were made for the lattice.
void check_grids(const Lattice& lattice, const HeadingGrids& grids, const BoundPyramid& pyramid) {
  validate(lattice, *grids.level().global, pyramid);
  const Lattice& own = grids.lattice();
  if (own.headings != lattice.headings || own.theta0 != lattice.theta0 ||
      own.step_theta != lattice.step_theta) {
    throw Error("branch and bound: the heading grids were made for another lattice");
  }
}

}  // namespace

SearchResult search_branch_and_bound(const Lattice& lattice, const HeadingGrids& grids,
                                     const BoundPyramid& pyramid,
                                     const BranchAndBoundOptions& options) {
  check_grids(lattice, grids, pyramid);
  return BranchAndBoundSearch(lattice, grids, pyramid, options).run();
}

struct ResumableBranchAndBound::Impl {
  Impl(const Lattice& lattice, const HeadingGrids& grids, const BoundPyramid& pyramid,
       BranchAndBoundOptions bnb)
      : options(std::move(bnb)), search(lattice, grids, pyramid, options) {}
  BranchAndBoundOptions options;  // before `search`, which holds a reference to it
  BranchAndBoundSearch search;
};

namespace {

BranchAndBoundOptions one_thread_unbudgeted(BranchAndBoundOptions options) {
  options.threads = 1;
  options.budget_ms = 0.0;
  return options;
}

}  // namespace

ResumableBranchAndBound::ResumableBranchAndBound(const Lattice& lattice, const HeadingGrids& grids,
                                                 const BoundPyramid& pyramid,
                                                 BranchAndBoundOptions options) {
  check_grids(lattice, grids, pyramid);
  impl_ =
      std::make_unique<Impl>(lattice, grids, pyramid, one_thread_unbudgeted(std::move(options)));
  impl_->search.begin();
}

ResumableBranchAndBound::~ResumableBranchAndBound() = default;

bool ResumableBranchAndBound::advance(long long cells) {
  return impl_->search.advance(cells);
}

bool ResumableBranchAndBound::done() const {
  return impl_->search.over();
}

double ResumableBranchAndBound::open_share() const {
  return impl_->search.open_share();
}

SearchResult ResumableBranchAndBound::take_result() {
  if (!done()) throw Error("branch and bound: the resumable search is not done yet");
  return impl_->search.take_result();
}

SearchResult search_branch_and_bound(const Lattice& lattice, const SearchLevel& finest,
                                     const BoundPyramid& pyramid,
                                     const std::optional<Exclusion>& exclude) {
  if (finest.global == nullptr) throw Error("branch and bound: the search level has no grid");
  validate(lattice, *finest.global, pyramid);
  const HeadingGrids grids(lattice, finest);
  grids.make_all();  // in parallel with finest.threads; the search itself runs on one
  BranchAndBoundOptions options;
  if (exclude) options.exclude.push_back(*exclude);
  return search_branch_and_bound(lattice, grids, pyramid, options);
}

}  // namespace gridloc
