#pragma once
// U, the useful region of a grid overlay (seed 002 §IV-D steps 5-6): private to the engine's
// grid overlay sources.
#include "gridloc/engine/disambiguation/grid_overlay.hpp"

namespace gridloc {

/// Marks overlay.useful: the OI cells crossed by a ray from an internal cell's centre that
/// stays in OI, within overlay.range (m; +inf: the lattice's diagonal) of that centre. 128 rays
/// per internal cell, split until neighbouring rays end at most a cell apart; stops once all
/// of OI is marked. Needs in_oi, internal and oi_count; returns the count of marked cells.
int mark_useful(GridOverlay& overlay);

}  // namespace gridloc
