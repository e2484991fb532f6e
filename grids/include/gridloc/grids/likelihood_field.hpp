#pragma once
/// A likelihood-field global grid (issue 13, item 3): each cell scores by its distance to the
/// nearest occupied map cell, as AMCL's likelihood field and real-time correlative scan
/// matching (Olson 2009) do, so that a return a cell or two off a wall still scores.
#include <vector>

#include "gridloc/grids/grid.hpp"

namespace gridloc {

/// Positive values of a likelihood field are whole multiples of 1 / kFieldLevels (and free
/// space one such multiple too), so that the engine's fixed-point kernel reads them from int8
/// copies exactly: 127 levels between 0 and 1.
inline constexpr int kFieldLevels = 127;

/// The likelihood field's parameters: a cell at distance d (m, centre to centre, exact
/// Euclidean) from the nearest occupied cell holds exp(-d^2 / (2 sigma^2)) while d <= cutoff
/// (1e-9 m of slack, so a cutoff of exactly k cells keeps the k-th cell);
/// beyond the cutoff a free cell holds free_value and any other cell 0. Every value is
/// rounded to a multiple of 1 / kFieldLevels. With sigma -> 0, cutoff 0 and free_value -1 it
/// is the raw signed grid (make_evidence).
struct LikelihoodFieldOptions {
  double sigma_m = 0.10;     ///< spread of the field around walls (m), > 0
  double cutoff_m = 0.20;    ///< the field reaches this far from a wall (m), >= 0
  double free_value = -1.0;  ///< free cells beyond the cutoff (free-space evidence), in [-1, 0]

  /// Throws gridloc::Error naming the field and its value when sigma is not a finite number
  /// in (0, 10] m, the cutoff not one in [0, 100] m, or free_value not one in [-1, 0].
  void validate() const;
};

/// The likelihood field of `map` at its own resolution (call it on each search level's
/// resampled map, never on a built grid). Distances come from the exact Euclidean
/// distance transform (squared_cell_distances). A map without an
/// occupied cell has no field: free cells get free_value, the others 0. Keeps the map's
/// geometry. Throws gridloc::Error for invalid options.
EvidenceGrid make_likelihood_field(const OccupancyMap& map, const LikelihoodFieldOptions& options);

/// The squared distance, in cells, from every cell's centre to the nearest occupied cell's
/// centre (row-major like the map's cells): exact whole numbers, from the linear-time exact
/// Euclidean distance transform of Felzenszwalb and Huttenlocher (2012); 1e30 everywhere
/// when the map has no occupied cell.
std::vector<double> squared_cell_distances(const OccupancyMap& map);

/// The field's value at distance `distance_m` from the nearest occupied cell, for a cell in
/// state `state`: what make_likelihood_field stores (quantized).
float likelihood_field_value(double distance_m, CellState state,
                             const LikelihoodFieldOptions& options);

}  // namespace gridloc
