#pragma once
/// The information a sensing point promises (seed 002 §IV-A): hypotheses whose views at the
/// point are the same form an equivalence class; sensing there keeps one class and rules out
/// the rest, so with k equally likely hypotheses in classes of sizes s_1..s_b the expected
/// number eliminated is info = sum_b (s_b / k)(k - s_b).
#include <vector>

#include "gridloc/engine/disambiguation/range_view.hpp"

namespace gridloc {

/// Seed 002's info for equivalence classes of the given sizes (each >= 1): 0 for one class,
/// k - 1 when every hypothesis stands alone. Throws gridloc::Error for a size below 1.
double expected_eliminations(const std::vector<int>& class_sizes);

/// The equivalence class of each view (0, 1, ... in order of first appearance): views that
/// are same_view() within `tolerance` of a class's first view share its class.
std::vector<int> equivalence_classes(const std::vector<RangeView>& views, double tolerance = 1e-6);

/// The size of each class of equivalence_classes().
std::vector<int> class_sizes(const std::vector<int>& classes);

}  // namespace gridloc
