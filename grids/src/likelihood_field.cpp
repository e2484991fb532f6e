// The likelihood-field global grid: an exact Euclidean distance transform of the occupied
// cells (Felzenszwalb and Huttenlocher), turned into quantized field values (issue 13).
#include "gridloc/grids/likelihood_field.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// Throws unless `value` is a finite number in [low, high] (open at low when `open_low`).
void check_range(const char* name, double value, double low, double high, bool open_low) {
  const bool above = open_low ? value > low : value >= low;
  if (above && value <= high && std::isfinite(value)) return;
  std::ostringstream m;
  m << "likelihood field: " << name << " must lie in " << (open_low ? "(" : "[") << low << ", "
    << high << "], got " << value;
  throw Error(m.str());
}

/// `value` rounded to the nearest multiple of 1 / kFieldLevels.
float quantize(double value) {
  return static_cast<float>(std::round(value * kFieldLevels)) / static_cast<float>(kFieldLevels);
}

/// Where no occupied cell is: larger than any squared distance on a grid of 2^31 cells.
constexpr double kFar = 1e30;

/// One pass of the exact squared Euclidean distance transform of Felzenszwalb and
/// Huttenlocher (2012): out[q] = min over p of (q - p)^2 + f[p], read off the lower envelope
/// of the parabolas rooted at each p with f[p] < kFar (`roots`; parabola i is the lowest
/// from `starts`[i] on). The values are whole numbers below 2^53 and an intersection lies
/// at least 1 / (2n) from any other whole number, so every comparison is exact.
void squared_distance_1d(const std::vector<double>& f, std::vector<double>& out,
                         std::vector<int>& roots, std::vector<double>& starts) {
  const int n = static_cast<int>(f.size());
  roots.clear();
  starts.clear();
  auto f_at = [&](int i) { return f[static_cast<std::size_t>(i)]; };
  for (int q = 0; q < n; ++q) {
    if (f_at(q) >= kFar) continue;
    double s = -kFar;
    while (!roots.empty()) {
      const int p = roots.back();
      s = ((f_at(q) + double(q) * q) - (f_at(p) + double(p) * p)) / (2.0 * (q - p));
      if (s > starts.back()) break;
      roots.pop_back();  // hidden by q's parabola from where it would start on
      starts.pop_back();
      s = -kFar;
    }
    roots.push_back(q);
    starts.push_back(s);
  }
  out.assign(static_cast<std::size_t>(n), kFar);
  std::size_t k = 0;
  for (int q = 0; q < n && !roots.empty(); ++q) {
    while (k + 1 < roots.size() && starts[k + 1] < q) ++k;
    const double d = q - roots[k];
    out[static_cast<std::size_t>(q)] = d * d + f_at(roots[k]);
  }
}

}  // namespace

std::vector<double> squared_cell_distances(const OccupancyMap& map) {
  const int w = map.width(), h = map.height();
  std::vector<double> d2(map.cells.size(), kFar);
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    if (map.cells[i] == CellState::Occupied) d2[i] = 0.0;
  }
  std::vector<double> line, out, starts;
  std::vector<int> roots;
  for (int ix = 0; ix < w; ++ix) {  // columns first, then rows
    line.resize(static_cast<std::size_t>(h));
    for (int iy = 0; iy < h; ++iy)
      line[static_cast<std::size_t>(iy)] = d2[map.geometry.index(ix, iy)];
    squared_distance_1d(line, out, roots, starts);
    for (int iy = 0; iy < h; ++iy)
      d2[map.geometry.index(ix, iy)] = out[static_cast<std::size_t>(iy)];
  }
  for (int iy = 0; iy < h; ++iy) {
    line.assign(d2.begin() + static_cast<std::ptrdiff_t>(map.geometry.index(0, iy)),
                d2.begin() + static_cast<std::ptrdiff_t>(map.geometry.index(0, iy)) + w);
    squared_distance_1d(line, out, roots, starts);
    std::copy(out.begin(), out.end(),
              d2.begin() + static_cast<std::ptrdiff_t>(map.geometry.index(0, iy)));
  }
  return d2;
}

void LikelihoodFieldOptions::validate() const {
  check_range("sigma_m", sigma_m, 0.0, 10.0, true);
  check_range("cutoff_m", cutoff_m, 0.0, 100.0, false);
  check_range("free_value", free_value, -1.0, 0.0, false);
}

float likelihood_field_value(double distance_m, CellState state,
                             const LikelihoodFieldOptions& options) {
  if (distance_m <= options.cutoff_m + 1e-9) {
    const double s = options.sigma_m;
    return quantize(std::exp(-distance_m * distance_m / (2.0 * s * s)));
  }
  return state == CellState::Free ? quantize(options.free_value) : 0.0f;
}

EvidenceGrid make_likelihood_field(const OccupancyMap& map, const LikelihoodFieldOptions& options) {
  options.validate();
  EvidenceGrid field(map.geometry, 0.0f);
  const std::vector<double> d2 = squared_cell_distances(map);
  const double res = map.geometry.resolution;
  for (std::size_t i = 0; i < d2.size(); ++i) {
    const double d = d2[i] >= kFar ? INFINITY : std::sqrt(d2[i]) * res;
    field.cells[i] = likelihood_field_value(d, map.cells[i], options);
  }
  return field;
}

}  // namespace gridloc
