#pragma once
/// The cells a ray crosses, in order and none skipped (Amanatides & Woo's traversal), shared
/// by the scan simulator, the log mapper and the disambiguation planner (issue 31).
#include <cmath>
#include <limits>

namespace gridloc {

/// A walk from the cell holding `(ox, oy)` (cell units: cell (i, j) covers [i, i + 1) x
/// [j, j + 1)) along `(dx, dy)`. `t` is the ray parameter, in units of the direction's
/// length, at which the walk entered the current cell (0 for the first).
struct CellWalk {
  CellWalk(double ox, double oy, double dx, double dy)
      : ix(static_cast<int>(std::floor(ox))),
        iy(static_cast<int>(std::floor(oy))),
        sx(dx > 0.0 ? 1 : -1),
        sy(dy > 0.0 ? 1 : -1),
        tdx(dx != 0.0 ? 1.0 / std::abs(dx) : kNever),
        tdy(dy != 0.0 ? 1.0 / std::abs(dy) : kNever),
        tx(dx != 0.0 ? (dx > 0.0 ? ix + 1 - ox : ox - ix) * tdx : kNever),
        ty(dy != 0.0 ? (dy > 0.0 ? iy + 1 - oy : oy - iy) * tdy : kNever) {}

  /// To the next cell the ray crosses (through the nearer cell boundary).
  void step() {
    if (tx < ty) {
      t = tx;
      tx += tdx;
      ix += sx;
    } else {
      t = ty;
      ty += tdy;
      iy += sy;
    }
  }

  /// One cell closer to (ex, ey) in x or y, whichever boundary the ray crosses first, but
  /// never past ex or ey: the walk always arrives at (ex, ey) (a beam's end cell), whatever
  /// the rounding. `t` is not kept.
  void step_towards(int ex, int ey) {
    if (iy == ey || (ix != ex && tx < ty)) {
      tx += tdx;
      ix += ex > ix ? 1 : -1;
    } else {
      ty += tdy;
      iy += ey > iy ? 1 : -1;
    }
  }

  static constexpr double kNever = std::numeric_limits<double>::infinity();
  int ix, iy;  ///< the current cell
  double t = 0.0;
  int sx, sy;       ///< the steps' signs
  double tdx, tdy;  ///< the parameter one cell's width and height take
  double tx, ty;    ///< the parameter at the next x and y boundaries
};

}  // namespace gridloc
