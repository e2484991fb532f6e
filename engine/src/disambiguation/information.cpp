#include "gridloc/engine/disambiguation/information.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

double expected_eliminations(const std::vector<int>& class_sizes) {
  const int total = std::accumulate(class_sizes.begin(), class_sizes.end(), 0);
  double info = 0.0;
  for (const int size : class_sizes) {
    if (size < 1) throw Error("an equivalence class has size " + std::to_string(size));
    info += static_cast<double>(size) / total * (total - size);  // seed 002 §IV-A
  }
  return info;
}

std::vector<int> equivalence_classes(const std::vector<RangeView>& views, double tolerance) {
  std::vector<int> classes(views.size(), -1);
  std::vector<std::size_t> first_of_class;
  for (std::size_t i = 0; i < views.size(); ++i) {
    for (std::size_t c = 0; c < first_of_class.size() && classes[i] < 0; ++c) {
      if (same_view(views[first_of_class[c]], views[i], tolerance))
        classes[i] = static_cast<int>(c);
    }
    if (classes[i] < 0) {
      classes[i] = static_cast<int>(first_of_class.size());
      first_of_class.push_back(i);
    }
  }
  return classes;
}

std::vector<int> class_sizes(const std::vector<int>& classes) {
  const int count = classes.empty() ? 0 : *std::max_element(classes.begin(), classes.end()) + 1;
  std::vector<int> sizes(static_cast<std::size_t>(count), 0);
  for (const int c : classes) ++sizes[static_cast<std::size_t>(c)];
  return sizes;
}

}  // namespace gridloc
