#include "gridloc/sensors/local_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace gridloc {

int SparseLocalGrid::extent() const {
  int e = 0;
  for (std::size_t k = 0; k < size(); ++k) e = std::max({e, std::abs(dx[k]), std::abs(dy[k])});
  return e;
}

double SparseLocalGrid::mass() const {
  double m = 0.0;
  for (float v : value) m += std::abs(v);
  return m;
}

}  // namespace gridloc
