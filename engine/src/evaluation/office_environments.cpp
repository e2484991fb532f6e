#include "gridloc/engine/evaluation/office_environments.hpp"

#include <algorithm>
#include <array>
#include <compare>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {
namespace {

/// A grid cell [x, x + 1] x [y, y + 1], or a cell step (a direction, a corner of the grid).
struct OfficeCell {
  int x = 0;
  int y = 0;
  auto operator<=>(const OfficeCell&) const = default;
};

OfficeCell operator+(OfficeCell a, OfficeCell b) {
  return {a.x + b.x, a.y + b.y};
}
OfficeCell operator-(OfficeCell a, OfficeCell b) {
  return {a.x - b.x, a.y - b.y};
}
OfficeCell operator*(int k, OfficeCell a) {
  return {k * a.x, k * a.y};
}

using CellSet = std::set<OfficeCell>;

/// The share of corridor branches that continue a corridor straight on past its far end (the
/// others leave a side at a right angle).
constexpr double kStraightOnShare = 0.3;

/// A straight corridor: cells at(i, j) for i in [0, length), j in [0, width); `along` and
/// `across` are unit steps at a right angle.
struct Corridor {
  OfficeCell origin;
  OfficeCell along;
  OfficeCell across;
  int length = 0;
  int width = 0;

  OfficeCell at(int i, int j) const { return origin + i * along + j * across; }
  /// The cell k cells out from side `side` (+1: the `across` side, -1: the other) at position
  /// i along the corridor; k = 0 is the corridor's own edge row.
  OfficeCell outward(int i, int side, int k) const { return at(i, side > 0 ? width - 1 + k : -k); }
};

/// A room in its corridor's frame: u along the corridor in [0, width), v away from it in
/// [0, depth); the door spans u in [door_offset, door_offset + door width). An L-shaped room
/// lacks the notch_width x notch_depth corner farthest from the corridor on one end.
struct RoomShape {
  int width = 0;
  int depth = 0;
  int door_offset = 0;
  int notch_width = 0;
  int notch_depth = 0;
  bool notch_at_start = false;

  bool contains(int u, int v) const {
    const bool in_notch_rows = v >= depth - notch_depth;
    const bool in_notch_columns = notch_at_start ? u < notch_width : u >= width - notch_width;
    return !(notch_width > 0 && in_notch_rows && in_notch_columns);
  }
};

/// Cells to add and how they join the office: `joint` must all be office cells already; no
/// other office cell may touch (8-neighbourhood) the piece except those in `allowed` (the
/// joint's row, one cell longer each way). So each piece keeps a one-cell wall from everything
/// but its joint, and the cell set stays simply connected.
struct Piece {
  std::vector<OfficeCell> cells;
  std::vector<OfficeCell> joint;
  std::vector<OfficeCell> allowed;
};

/// The joint row of a piece that leaves side `side` of `corridor` at positions [i0, i0 + span).
void add_joint(Piece& piece, const Corridor& corridor, int side, int i0, int span) {
  for (int i = i0 - 1; i <= i0 + span; ++i) {
    piece.allowed.push_back(corridor.outward(i, side, 0));
    if (i >= i0 && i < i0 + span) piece.joint.push_back(corridor.outward(i, side, 0));
  }
}

/// seed 002 §V's offices: a room starting at position `start` of `side`, behind a one-cell
/// wall pierced by its door.
Piece room_piece(const Corridor& corridor, int side, int start, const RoomShape& shape,
                 int door_width) {
  Piece piece;
  for (int u = 0; u < door_width; ++u) {
    piece.cells.push_back(corridor.outward(start + shape.door_offset + u, side, 1));
  }
  for (int u = 0; u < shape.width; ++u) {
    for (int v = 0; v < shape.depth; ++v) {
      if (shape.contains(u, v)) piece.cells.push_back(corridor.outward(start + u, side, 2 + v));
    }
  }
  add_joint(piece, corridor, side, start + shape.door_offset, door_width);
  return piece;
}

/// The corridor of `width` branching off side `side` of `parent` at positions [i0, i0 + width).
Corridor branch_corridor(const Corridor& parent, int side, int i0, int length, int width) {
  return {parent.outward(i0, side, 1), side * parent.across, parent.along, length, width};
}

/// The same cells seen with along and across swapped: its side +1 is the corridor's far end.
Corridor transposed(const Corridor& c) {
  return {c.origin, c.across, c.along, c.width, c.length};
}

std::vector<OfficeCell> corridor_cells(const Corridor& corridor) {
  std::vector<OfficeCell> cells;
  for (int i = 0; i < corridor.length; ++i) {
    for (int j = 0; j < corridor.width; ++j) cells.push_back(corridor.at(i, j));
  }
  return cells;
}

/// A corridor branch (from branch_corridor) as a piece joining its parent.
Piece corridor_piece(const Corridor& parent, int side, const Corridor& branch, int i0) {
  Piece piece{corridor_cells(branch), {}, {}};
  add_joint(piece, parent, side, i0, branch.width);
  return piece;
}

/// Whether the piece can join the office under Piece's rule.
bool fits(const CellSet& office, const Piece& piece) {
  for (const OfficeCell& c : piece.joint) {
    if (!office.contains(c)) return false;
  }
  const CellSet allowed(piece.allowed.begin(), piece.allowed.end());
  for (const OfficeCell& c : piece.cells) {
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        const OfficeCell q = c + OfficeCell{dx, dy};
        if (office.contains(q) && !allowed.contains(q)) return false;
      }
    }
  }
  return true;
}

/// Whether grid corner `corner` is a vertex of the cell set's boundary: one or three of the
/// four cells around it are in the set (two diagonal ones, which Piece's rule never makes,
/// would count once though they make two).
bool is_vertex(const CellSet& cells, OfficeCell corner) {
  int around = 0;
  for (const OfficeCell d :
       {OfficeCell{-1, -1}, OfficeCell{0, -1}, OfficeCell{-1, 0}, OfficeCell{0, 0}}) {
    around += cells.contains(corner + d) ? 1 : 0;
  }
  return around == 1 || around == 3;
}

/// The corners of the cells (each cell's four), without repeats.
CellSet corners_of(const std::vector<OfficeCell>& cells) {
  CellSet corners;
  for (const OfficeCell& c : cells) {
    for (const OfficeCell d :
         {OfficeCell{0, 0}, OfficeCell{1, 0}, OfficeCell{0, 1}, OfficeCell{1, 1}}) {
      corners.insert(c + d);
    }
  }
  return corners;
}

/// How many of the corners are vertices of the cell set's boundary.
int vertices_at(const CellSet& cells, const CellSet& corners) {
  int vertices = 0;
  for (const OfficeCell& corner : corners) vertices += is_vertex(cells, corner) ? 1 : 0;
  return vertices;
}

/// The boundary edges of the cell set, each unit edge from its start corner to its end corner
/// with the cells on its left (so the outer boundary runs counter-clockwise).
std::map<OfficeCell, OfficeCell> boundary_edges(const CellSet& cells) {
  // Per side of a cell: the neighbour across it, the edge's start and end corner offsets.
  static constexpr std::array<std::array<OfficeCell, 3>, 4> kSides{{
      {{{0, -1}, {0, 0}, {1, 0}}},  // bottom
      {{{1, 0}, {1, 0}, {1, 1}}},   // right
      {{{0, 1}, {1, 1}, {0, 1}}},   // top
      {{{-1, 0}, {0, 1}, {0, 0}}},  // left
  }};
  std::map<OfficeCell, OfficeCell> next;
  for (const OfficeCell& c : cells) {
    for (const auto& [neighbour, from, to] : kSides) {
      if (cells.contains(c + neighbour)) continue;
      if (!next.emplace(c + from, c + to).second) {
        throw Error("random_office: cells touch only at corner (" + std::to_string(c.x + from.x) +
                    ", " + std::to_string(c.y + from.y) + ")");
      }
    }
  }
  return next;
}

/// The boundary of the cell set as one counter-clockwise ring of cell corners without
/// collinear vertices; throws gridloc::Error if the set has a hole or is not one piece.
std::vector<OfficeCell> trace_boundary(const CellSet& cells) {
  const std::map<OfficeCell, OfficeCell> next = boundary_edges(cells);
  std::vector<OfficeCell> corners;
  const OfficeCell start = next.begin()->first;
  OfficeCell at = start;
  do {
    corners.push_back(at);
    at = next.at(at);
  } while (at != start && corners.size() <= next.size());
  if (corners.size() != next.size()) {
    throw Error("random_office: the cells' boundary is not one ring (a hole or two pieces)");
  }
  std::vector<OfficeCell> ring;
  const std::size_t n = corners.size();
  for (std::size_t k = 0; k < n; ++k) {
    const OfficeCell in = corners[k] - corners[(k + n - 1) % n];
    const OfficeCell out = corners[(k + 1) % n] - corners[k];
    if (in != out) ring.push_back(corners[k]);
  }
  return ring;
}

void check_range(int lo, int hi, const std::string& name) {
  if (lo < 1 || hi < lo) {
    throw Error("random_office: " + name + " must satisfy 1 <= min <= max, got " +
                std::to_string(lo) + " and " + std::to_string(hi));
  }
}

void check_at_most(int value, int most, const std::string& name, const std::string& bound) {
  if (value < 1 || value > most) {
    throw Error("random_office: " + name + " must be in [1, " + bound + " = " +
                std::to_string(most) + "], got " + std::to_string(value));
  }
}

void check_options(const OfficeOptions& o) {
  const ResourceLimits limits;
  if (o.target_vertices < 4 || o.target_vertices > limits.max_vertices) {
    throw Error("random_office: target_vertices must be in [4, " +
                std::to_string(static_cast<long>(limits.max_vertices)) +
                "] (the polygon map vertex limit), got " + std::to_string(o.target_vertices));
  }
  check_range(o.min_room_width, o.max_room_width, "room width");
  check_range(o.min_room_depth, o.max_room_depth, "room depth");
  check_range(o.min_corridor_length, o.max_corridor_length, "corridor length");
  check_at_most(o.corridor_width, o.max_corridor_length, "corridor_width", "max_corridor_length");
  check_at_most(o.door_width, o.min_room_width, "door_width", "min_room_width");
  require_share(o.repeat_probability, "random_office", "repeat_probability");
  require_share(o.notch_probability, "random_office", "notch_probability");
  require_share(o.branch_probability, "random_office", "branch_probability");
  require_positive(o.resolution, "random_office", "resolution");
}

/// Grows one office from its seed: pieces drawn in a fixed order of Rng calls (no std
/// distribution, whose streams differ between standard libraries).
class OfficeBuilder {
 public:
  OfficeBuilder(std::uint64_t seed, const OfficeOptions& options)
      : rng_(seed), options_(options), seed_(seed) {
    const Corridor first{
        {0, 0}, {1, 0}, {0, 1}, options.max_corridor_length, options.corridor_width};
    place(Piece{corridor_cells(first), {}, {}});  // fits the empty office
    corridors_.push_back(first);
  }

  /// seed 002 §V: pieces until the boundary has target_vertices vertices; the boundary.
  std::vector<OfficeCell> build() {
    for (int attempt = 0; vertices_ < options_.target_vertices; ++attempt) {
      if (attempt >= options_.max_attempts) {
        throw Error("random_office: seed " + std::to_string(seed_) + " reached " +
                    std::to_string(vertices_) + " of " + std::to_string(options_.target_vertices) +
                    " vertices in " + std::to_string(options_.max_attempts) +
                    " pieces tried (max_attempts)");
      }
      if (chance(options_.branch_probability)) {
        try_branch();
      } else {
        try_room();
      }
    }
    std::vector<OfficeCell> ring = trace_boundary(office_);
    if (static_cast<int>(ring.size()) != vertices_) {
      throw Error("random_office: the traced boundary has " + std::to_string(ring.size()) +
                  " vertices, the count says " + std::to_string(vertices_));
    }
    return ring;
  }

 private:
  /// Where the next room of the current row goes: rooms side by side, one wall cell apart.
  struct RowCursor {
    std::size_t corridor = 0;
    int side = 1;
    int start = 0;
  };

  int uniform_int(int lo, int hi) {  // in [lo, hi]; the modulo's bias is below 2^-40
    return lo + static_cast<int>(rng_.next() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  bool chance(double p) { return rng_.uniform() < p; }
  int random_side() { return chance(0.5) ? 1 : -1; }

  std::size_t random_corridor() {
    return static_cast<std::size_t>(uniform_int(0, static_cast<int>(corridors_.size()) - 1));
  }

  /// Adds the piece if it fits, counting the boundary vertices it removes and adds (only
  /// corners of its cells change).
  bool place(const Piece& piece) {
    if (!fits(office_, piece)) return false;
    const CellSet corners = corners_of(piece.cells);
    vertices_ -= vertices_at(office_, corners);
    office_.insert(piece.cells.begin(), piece.cells.end());
    vertices_ += vertices_at(office_, corners);
    return true;
  }

  /// A corridor continuing a random corridor past its far end, or leaving one of its sides;
  /// as long as fits, down to min_corridor_length.
  bool try_branch() {
    const Corridor& picked = corridors_[random_corridor()];
    const int width = options_.corridor_width;
    const bool straight_on = chance(kStraightOnShare);
    const Corridor parent = straight_on ? transposed(picked) : picked;
    const int side = straight_on ? 1 : random_side();
    const int i0 = straight_on ? 0 : uniform_int(0, parent.length - width);
    const int length = uniform_int(options_.min_corridor_length, options_.max_corridor_length);
    for (int l = length; l >= options_.min_corridor_length; --l) {
      const Corridor branch = branch_corridor(parent, side, i0, l, width);
      if (place(corridor_piece(parent, side, branch, i0))) {
        corridors_.push_back(branch);
        return true;
      }
    }
    return false;
  }

  /// seed 002 §V's self-similarity: most rooms repeat the previous room's shape.
  RoomShape next_shape() {
    if (previous_ && chance(options_.repeat_probability)) return *previous_;
    RoomShape shape;
    shape.width = uniform_int(options_.min_room_width, options_.max_room_width);
    shape.depth = uniform_int(options_.min_room_depth, options_.max_room_depth);
    shape.door_offset = uniform_int(0, shape.width - options_.door_width);
    if (shape.width >= 2 && shape.depth >= 2 && chance(options_.notch_probability)) {
      shape.notch_width = uniform_int(1, shape.width - 1);
      shape.notch_depth = uniform_int(1, shape.depth - 1);
      shape.notch_at_start = chance(0.5);
    }
    return shape;
  }

  /// The next room of the current row, or the first of a new row at a random place; a room
  /// that does not fit ends its row.
  bool try_room() {
    if (!row_) {
      const std::size_t corridor = random_corridor();
      const int side = random_side();
      row_ = RowCursor{corridor, side, uniform_int(0, corridors_[corridor].length - 1)};
    }
    const Corridor& corridor = corridors_[row_->corridor];
    const RoomShape shape = next_shape();
    // Rooms stay within their corridor's length, leaving its far end free to continue.
    if (row_->start + shape.width > corridor.length ||
        !place(room_piece(corridor, row_->side, row_->start, shape, options_.door_width))) {
      row_.reset();
      return false;
    }
    previous_ = shape;
    row_->start += shape.width + 1;
    return true;
  }

  Rng rng_;
  const OfficeOptions& options_;
  std::uint64_t seed_;
  CellSet office_;
  int vertices_ = 0;  ///< of office_'s boundary
  std::vector<Corridor> corridors_;
  std::optional<RoomShape> previous_;
  std::optional<RowCursor> row_;
};

}  // namespace

PolygonMap random_office(std::uint64_t seed, const OfficeOptions& options) {
  check_options(options);
  const std::vector<OfficeCell> ring = OfficeBuilder(seed, options).build();
  OfficeCell lowest = ring.front();
  for (const OfficeCell& c : ring) lowest = {std::min(lowest.x, c.x), std::min(lowest.y, c.y)};
  Polygon boundary;
  for (const OfficeCell& c : ring) boundary.emplace_back(c.x - lowest.x, c.y - lowest.y);
  return make_polygon_map(std::move(boundary), {}, options.resolution);
}

}  // namespace gridloc
