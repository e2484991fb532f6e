// The variants of cyclic labels: M m pairs left out of a label, D c pairs left out of its
// skeleton, and the maxima between two positions.
#include "label_variants.hpp"

#include <algorithm>
#include <utility>

namespace gridloc::sectors_detail {
namespace {

bool is_pair(char a, char b) {
  return (a == 'M' && b == 'm') || (a == 'm' && b == 'M');
}

}  // namespace

/// The label itself and every label with up to `pairs` neighbouring M m pairs deleted (the
/// label is cyclic: its last and first characters are neighbours too).
std::vector<Variant> variants(const std::string& label, int pairs) {
  std::vector<Variant> out;
  Variant full{label, {}};
  for (int i = 0; i < static_cast<int>(label.size()); ++i) full.index.push_back(i);
  out.push_back(full);
  std::size_t from = 0;
  for (int round = 0; round < pairs; ++round) {
    const std::size_t to = out.size();
    for (std::size_t v = from; v < to; ++v) {
      const int n = static_cast<int>(out[v].label.size());
      for (int i = 0; i < n && n >= 2; ++i) {
        const int j = (i + 1) % n;
        if (!is_pair(out[v].label[i], out[v].label[j])) continue;
        Variant shorter;
        for (int k = 0; k < n; ++k) {
          if (k == i || k == j) continue;
          shorter.label.push_back(out[v].label[k]);
          shorter.index.push_back(out[v].index[k]);
        }
        const bool seen = std::any_of(out.begin(), out.end(),
                                      [&](const Variant& x) { return x.index == shorter.index; });
        if (!seen) out.push_back(std::move(shorter));
      }
    }
    from = to;
  }
  return out;
}

/// The positions of a label's D and c characters: the jumps of a scan, which a partial view
/// keeps while the extrema between them come and go.
std::vector<int> skeleton(const std::string& label) {
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(label.size()); ++i) {
    if (label[i] == 'D' || label[i] == 'c') out.push_back(i);
  }
  return out;
}

/// The skeleton itself and every skeleton with up to `pairs` neighbouring D c (or c D) pairs
/// left out (cyclic, like the label).
std::vector<std::vector<int>> skeleton_variants(const std::string& label,
                                                const std::vector<int>& skeleton, int pairs) {
  std::vector<std::vector<int>> out{skeleton};
  std::size_t from = 0;
  for (int round = 0; round < pairs; ++round) {
    const std::size_t to = out.size();
    for (std::size_t v = from; v < to; ++v) {
      const int n = static_cast<int>(out[v].size());
      for (int i = 0; i < n && n >= 4; ++i) {
        const int j = (i + 1) % n;
        if (label[out[v][i]] == label[out[v][j]]) continue;  // DD or cc: not a pair
        std::vector<int> shorter;
        for (int k = 0; k < n; ++k) {
          if (k != i && k != j) shorter.push_back(out[v][k]);
        }
        if (std::find(out.begin(), out.end(), shorter) == out.end())
          out.push_back(std::move(shorter));
      }
    }
    from = to;
  }
  return out;
}

/// The positions of the M characters strictly between positions `from` and `to` of a cyclic
/// label (from == to: the whole label but `from`).
std::vector<int> maxima_between(const std::string& label, int from, int to) {
  std::vector<int> out;
  const int n = static_cast<int>(label.size());
  for (int i = (from + 1) % n; i != to; i = (i + 1) % n) {
    if (label[i] == 'M') out.push_back(i);
  }
  return out;
}

}  // namespace gridloc::sectors_detail
