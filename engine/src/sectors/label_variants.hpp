#pragma once
// The variants of cyclic labels the sectors' localization matches (internal): labels with M m
// pairs left out, and skeletons (the D and c characters) with D c pairs left out.
#include <string>
#include <vector>

namespace gridloc::sectors_detail {

/// A label with some neighbouring M m pairs left out; `index` gives each kept character's
/// position in the full label.
struct Variant {
  std::string label;
  std::vector<int> index;
};

/// The label itself and every label with up to `pairs` neighbouring M m pairs deleted.
std::vector<Variant> variants(const std::string& label, int pairs);

/// The positions of a label's D and c characters (its jumps).
std::vector<int> skeleton(const std::string& label);

/// The skeleton itself and every skeleton with up to `pairs` neighbouring D c pairs left out.
std::vector<std::vector<int>> skeleton_variants(const std::string& label,
                                                const std::vector<int>& skeleton, int pairs);

/// The positions of the M characters strictly between positions `from` and `to` (cyclic).
std::vector<int> maxima_between(const std::string& label, int from, int to);

}  // namespace gridloc::sectors_detail
