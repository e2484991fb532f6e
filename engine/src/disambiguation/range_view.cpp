#include "gridloc/engine/disambiguation/range_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/planar.hpp"

namespace gridloc {

namespace {

constexpr double kVertexTolerance = 1e-9;     // an end this close to an area vertex is one
constexpr double kMinPieceLength = 1e-9;      // shorter pieces are left out (range_view.hpp)
constexpr double kOnBoundaryDistance = 1e-9;  // a viewpoint this close to a wall stands on it
constexpr double kDuplicatePoint = 1e-10;     // visibility polygon vertices merged when closer

/// A monotone stand-in for atan2 with the range [-pi, pi) mapped to [-2, 2): -2 on the -x
/// axis, rising counter-clockwise. Cheaper than atan2 and exact for equal directions.
double pseudo_angle(const Eigen::Vector2d& v) {
  const double ratio = v.y() / (std::abs(v.x()) + std::abs(v.y()));
  if (v.x() >= 0.0) return ratio;
  if (v.y() == 0.0) return -2.0;
  return v.y() > 0.0 ? 2.0 - ratio : -2.0 - ratio;
}

/// The change from world to viewer frame: subtract the viewpoint, turn by -heading.
struct ViewerFrame {
  Eigen::Vector2d origin;
  double cos_heading = 1.0, sin_heading = 0.0;

  Eigen::Vector2d operator()(const Eigen::Vector2d& world) const {
    const Eigen::Vector2d d = world - origin;
    return {cos_heading * d.x() + sin_heading * d.y(), -sin_heading * d.x() + cos_heading * d.y()};
  }
};

/// Whether the segment a-b lies wholly on one side outside the square of half-side `range`
/// about p (then it is farther than `range` from p): a cheap first filter.
bool beyond_box(const Eigen::Vector2d& p, double range, const Eigen::Vector2d& a,
                const Eigen::Vector2d& b) {
  return (a.x() < p.x() - range && b.x() < p.x() - range) ||
         (a.x() > p.x() + range && b.x() > p.x() + range) ||
         (a.y() < p.y() - range && b.y() < p.y() - range) ||
         (a.y() > p.y() + range && b.y() > p.y() + range);
}

/// A wall in the viewer frame, `start` its counter-clockwise-first end as seen from the
/// viewpoint (the origin). `facing`: the area side looks at the viewer (only those can be
/// seen; the others only block rays, for a viewpoint on the boundary).
struct SweepEdge {
  Eigen::Vector2d start, end;
  bool facing = true;
};

/// One angular interval of the sweep, `from` to `to` counter-clockwise (directions of any
/// length: vertices, or the -x axis; pseudo angles `from_key` < `to_key`), with the nearest
/// wall throughout it (-1: none).
struct SweepInterval {
  Eigen::Vector2d from, to;
  double from_key = -2.0, to_key = 2.0;
  int edge = -1;
};

/// A direction where walls open or close: the vertex where `close` ends and `open` starts
/// (-1: none), so a vertex shared by two consecutive walls is one event.
struct SweepEvent {
  double key;
  int open = -1;
  int close = -1;
};

/// The walls that may matter: within `range` of the viewpoint, not seen edge-on, facing the
/// viewer (back faces too when the viewpoint stands on a wall), in the viewer frame.
std::vector<SweepEdge> sweep_edges(const Area& area, const ViewerFrame& frame, double range) {
  const double range2 = range * range;  // +inf for kUnlimitedRange
  const double boundary2 = kOnBoundaryDistance * kOnBoundaryDistance;
  const bool finite = std::isfinite(range);
  std::vector<SweepEdge> edges;
  std::vector<std::pair<const Eigen::Vector2d*, const Eigen::Vector2d*>> back_faces;
  edges.reserve(area.outer.size() + 4 * area.holes.size());
  bool on_boundary = false;
  auto collect = [&](const Polygon& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& a = ring[i];
      const Eigen::Vector2d& b = ring[i + 1 < ring.size() ? i + 1 : 0];
      if (finite && beyond_box(frame.origin, range, a, b)) continue;
      const double turn = cross(a - frame.origin, b - frame.origin);  // > 0: area faces viewer
      // Twice the triangle's area bounds the distance to the wall's line: test only near ones.
      if (turn * turn <= boundary2 * (b - a).squaredNorm()) {
        on_boundary = on_boundary || squared_distance_to_segment(frame.origin, a, b) <= boundary2;
      }
      if (finite && squared_distance_to_segment(frame.origin, a, b) > range2) continue;
      if (turn > 0.0) edges.push_back({frame(a), frame(b), true});
      if (turn < 0.0) back_faces.emplace_back(&a, &b);
    }
  };
  collect(area.outer);
  for (const Polygon& hole : area.holes) collect(hole);
  if (!on_boundary) return edges;
  for (const auto& [a, b] : back_faces) edges.push_back({frame(*b), frame(*a), false});
  return edges;
}

/// A direction strictly inside the counter-clockwise turn from u to v, of any lengths: a
/// positive combination lies inside a turn below pi, a negative one inside a turn above it.
Eigen::Vector2d bisector(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  Eigen::Vector2d mid = u + v;
  const double turn = cross(u, v);
  if (turn < 0.0 || (turn == 0.0 && u.dot(v) < 0.0)) mid = -mid;  // a turn of pi or more
  if (mid.squaredNorm() <= 1e-24 * (u.squaredNorm() + v.squaredNorm())) {
    mid = Eigen::Vector2d(-u.y(), u.x());
  }
  return mid;
}

/// The wall hit first by the ray from the origin along `direction` among `candidates`, or -1.
int nearest_edge(const std::vector<SweepEdge>& edges, const std::vector<int>& candidates,
                 const Eigen::Vector2d& direction) {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const int e : candidates) {
    const Eigen::Vector2d d = edges[e].end - edges[e].start;
    const double distance = cross(edges[e].start, d) / cross(direction, d);
    if (distance > 0.0 && distance < best_distance) best_distance = distance, best = e;
  }
  return best;
}

/// The events in counter-clockwise order from the -x axis; walls crossing it are returned in
/// `initially_active`. `edges` come in ring order, so a wall starting where the previous one
/// ends shares its event.
std::vector<SweepEvent> sweep_events(const std::vector<SweepEdge>& edges,
                                     std::vector<int>& initially_active) {
  std::vector<SweepEvent> events;
  events.reserve(2 * edges.size());
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    const double open = pseudo_angle(edges[e].start), close = pseudo_angle(edges[e].end);
    if (open == close) continue;                      // degenerate: no angular extent
    if (close < open) initially_active.push_back(e);  // crosses the -x axis
    const bool shared = !events.empty() && events.back().close == e - 1 && events.back().open < 0 &&
                        edges[e - 1].end == edges[e].start;
    if (shared) {
      events.back().open = e;
    } else {
      events.push_back({open, e, -1});
    }
    events.push_back({close, -1, e});
  }
  // Stable: the input is nearly sorted (facing walls along a ring turn counter-clockwise).
  std::stable_sort(events.begin(), events.end(),
                   [](const SweepEvent& l, const SweepEvent& r) { return l.key < r.key; });
  return events;
}

/// The set of walls the sweep ray crosses; O(1) insertion and removal.
class ActiveSet {
 public:
  explicit ActiveSet(std::size_t edges) : position_(edges, -1) {}
  void insert(int e) {
    if (position_[e] >= 0) return;
    position_[e] = static_cast<int>(members_.size());
    members_.push_back(e);
  }
  void erase(int e) {
    if (position_[e] < 0) return;
    const int last = members_.back();
    members_[position_[e]] = last;
    position_[last] = position_[e];
    members_.pop_back();
    position_[e] = -1;
  }
  const std::vector<int>& members() const { return members_; }

 private:
  std::vector<int> position_;
  std::vector<int> members_;
};

/// The nearest wall as the sweep turns. Walls do not cross, so between events it stays the
/// same, and at an event it changes only to a wall that opens there, or when it closes.
class NearestWall {
 public:
  explicit NearestWall(const std::vector<SweepEdge>& edges)
      : edges_(edges), active_(edges.size()) {}
  void open(int e) { active_.insert(e), opened_.push_back(e); }
  void close(int e) {
    active_.erase(e);
    if (e == nearest_) rescan_ = true;
  }
  /// The nearest wall over an interval with no event inside; `direction` lies inside it.
  int over(const Eigen::Vector2d& direction) {
    if (rescan_) {
      nearest_ = nearest_edge(edges_, active_.members(), direction);
    } else if (!opened_.empty()) {
      if (nearest_ >= 0) opened_.push_back(nearest_);
      nearest_ = nearest_edge(edges_, opened_, direction);
    }
    rescan_ = nearest_ < 0 && !active_.members().empty();  // rounding found no hit: retry
    opened_.clear();
    return nearest_;
  }

 private:
  const std::vector<SweepEdge>& edges_;
  ActiveSet active_;
  std::vector<int> opened_;  // since the last interval
  int nearest_ = -1;
  bool rescan_ = true;
};

/// The angular sweep (seed 002 §III-B's W): between consecutive vertex directions the nearest
/// wall is fixed, so one ray per interval finds it. Intervals cover [-pi, pi) in order.
std::vector<SweepInterval> sweep(const std::vector<SweepEdge>& edges) {
  std::vector<int> initially_active;
  const std::vector<SweepEvent> events = sweep_events(edges, initially_active);
  NearestWall nearest(edges);
  for (const int e : initially_active) nearest.open(e);
  std::vector<SweepInterval> intervals;
  intervals.reserve(events.size() / 2 + 2);
  SweepInterval current{{-1.0, 0.0}, {-1.0, 0.0}, -2.0, 2.0, -1};
  for (std::size_t i = 0; i < events.size();) {
    const double key = events[i].key;
    if (key > current.from_key) {
      const SweepEvent& event = events[i];
      current.to = event.open >= 0 ? edges[event.open].start : edges[event.close].end;
      current.to_key = key;
      current.edge = nearest.over(bisector(current.from, current.to));
      intervals.push_back(current);
      current = {current.to, {-1.0, 0.0}, key, 2.0, -1};
    }
    for (; i < events.size() && events[i].key == key; ++i) {
      if (events[i].close >= 0) nearest.close(events[i].close);
      if (events[i].open >= 0) nearest.open(events[i].open);
    }
  }
  current.edge = nearest.over(bisector(current.from, current.to));
  intervals.push_back(current);
  return intervals;
}

/// The parameter t of the point start + t (end - start) of the edge's line on the ray along
/// `direction`, clamped to the edge.
double edge_parameter(const SweepEdge& edge, const Eigen::Vector2d& direction) {
  const Eigen::Vector2d d = edge.end - edge.start;
  return std::clamp(cross(edge.start, direction) / cross(direction, d), 0.0, 1.0);
}

/// The parameters [t0, t1] of the edge inside the disk of `range` about the origin; false when
/// the edge's line misses the disk.
bool disk_parameters(const SweepEdge& edge, double range, double& t0, double& t1) {
  if (std::isinf(range)) return t0 = 0.0, t1 = 1.0, true;
  const Eigen::Vector2d d = edge.end - edge.start;
  const double a = d.squaredNorm(), half_b = edge.start.dot(d);
  const double c = edge.start.squaredNorm() - range * range;
  const double discriminant = half_b * half_b - a * c;
  if (discriminant < 0.0) return false;
  const double root = std::sqrt(discriminant);
  t0 = (-half_b - root) / a, t1 = (-half_b + root) / a;
  return true;
}

/// A piece as edge parameters, before it becomes a ViewPiece.
struct EdgeRun {
  int edge;
  double t0, t1;
};

/// The visible parameter runs of the intervals' walls, clipped to the disk, with contiguous
/// runs of one edge merged (seam at the -x axis kept), so congruent views give equal lists.
std::vector<EdgeRun> visible_runs(const std::vector<SweepEdge>& edges,
                                  const std::vector<SweepInterval>& intervals, double range) {
  std::vector<EdgeRun> runs;
  for (const SweepInterval& interval : intervals) {
    if (interval.edge < 0 || !edges[interval.edge].facing) continue;
    const SweepEdge& edge = edges[interval.edge];
    double disk0 = 0.0, disk1 = 0.0;
    if (!disk_parameters(edge, range, disk0, disk1)) continue;
    const double t0 = std::max(edge_parameter(edge, interval.from), disk0);
    const double t1 = std::min(edge_parameter(edge, interval.to), disk1);
    if (t0 >= t1) continue;
    if (!runs.empty() && runs.back().edge == interval.edge &&
        std::abs(runs.back().t1 - t0) <= 1e-12) {
      runs.back().t1 = t1;
    } else {
      runs.push_back({interval.edge, t0, t1});
    }
  }
  return runs;
}

/// The point at parameter t of the edge, snapped to an end within kVertexTolerance.
Eigen::Vector2d run_point(const SweepEdge& edge, double t, bool& is_vertex) {
  Eigen::Vector2d point = edge.start + t * (edge.end - edge.start);
  is_vertex = true;
  if ((point - edge.start).norm() <= kVertexTolerance) return edge.start;
  if ((point - edge.end).norm() <= kVertexTolerance) return edge.end;
  is_vertex = false;
  return point;
}

void check_view_input(const Eigen::Vector2d& viewpoint, double heading, double range) {
  if (!viewpoint.allFinite()) throw Error("range_view: the viewpoint is not finite");
  if (!std::isfinite(heading)) throw Error("range_view: the heading is not finite");
  if (!(range > 0.0)) throw Error("range_view: range must be > 0, got " + std::to_string(range));
}

std::vector<SweepEdge> edges_seen_from(const Area& area, const Eigen::Vector2d& viewpoint,
                                       double heading, double range) {
  check_view_input(viewpoint, heading, range);
  if (area.outer.size() < 3) throw Error("range_view: the area's outer ring has < 3 vertices");
  const ViewerFrame frame{viewpoint, std::cos(heading), std::sin(heading)};
  return sweep_edges(area, frame, range);
}

}  // namespace

RangeView range_view(const Area& area, const Eigen::Vector2d& viewpoint, double heading,
                     double range) {
  const std::vector<SweepEdge> edges = edges_seen_from(area, viewpoint, heading, range);
  RangeView view;
  for (const EdgeRun& run : visible_runs(edges, sweep(edges), range)) {
    ViewPiece piece;
    piece.segment.a = run_point(edges[run.edge], run.t0, piece.a_is_vertex);
    piece.segment.b = run_point(edges[run.edge], run.t1, piece.b_is_vertex);
    if ((piece.segment.b - piece.segment.a).norm() >= kMinPieceLength) {
      view.pieces.push_back(piece);
    }
  }
  return view;
}

bool same_view(const RangeView& first, const RangeView& second, double tolerance) {
  if (first.pieces.size() != second.pieces.size()) return false;
  for (std::size_t i = 0; i < first.pieces.size(); ++i) {
    const ViewPiece& l = first.pieces[i];
    const ViewPiece& r = second.pieces[i];
    if (l.a_is_vertex != r.a_is_vertex || l.b_is_vertex != r.b_is_vertex) return false;
    if ((l.segment.a - r.segment.a).norm() > tolerance) return false;
    if ((l.segment.b - r.segment.b).norm() > tolerance) return false;
  }
  return true;
}

int visible_vertex_count(const RangeView& view) {
  std::vector<std::pair<double, double>> vertices;
  for (const ViewPiece& piece : view.pieces) {
    if (piece.a_is_vertex) vertices.emplace_back(piece.segment.a.x(), piece.segment.a.y());
    if (piece.b_is_vertex) vertices.emplace_back(piece.segment.b.x(), piece.segment.b.y());
  }
  std::sort(vertices.begin(), vertices.end());  // ends are snapped: one vertex, one value
  return static_cast<int>(std::unique(vertices.begin(), vertices.end()) - vertices.begin());
}

namespace {

/// The counter-clockwise angle from the interval's start to its end, in (0, 2 pi].
double interval_span(const SweepInterval& interval) {
  double span = std::atan2(cross(interval.from, interval.to), interval.from.dot(interval.to));
  if (span < 0.0 || (span == 0.0 && interval.to_key > interval.from_key)) {
    span += 2.0 * std::numbers::pi;
  }
  return span;
}

/// Appends the arc of radius `range` from direction `from` turning by `span` (rad) with
/// chords of at most `max_chord_angle`.
void append_arc(const Eigen::Vector2d& from, double span, double range, double max_chord_angle,
                Polygon& ring) {
  const int chords = std::max(1, static_cast<int>(std::ceil(span / max_chord_angle - 1e-12)));
  const Eigen::Vector2d unit = from.normalized();
  for (int j = 0; j <= chords; ++j) {
    const double angle = span * j / chords;
    const double c = std::cos(angle), s = std::sin(angle);
    ring.push_back(range *
                   Eigen::Vector2d(c * unit.x() - s * unit.y(), s * unit.x() + c * unit.y()));
  }
}

void append_arc_between(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double range,
                        double max_chord_angle, Polygon& ring) {
  const double span = std::atan2(cross(from, to), from.dot(to));
  if (span > 0.0) append_arc(from, span, range, max_chord_angle, ring);
}

/// The boundary of the seen region over an interval whose nearest wall faces the viewer: the
/// wall where it is within range, arcs of the range circle where it is not (seed 002 §IV-B:
/// nothing beyond d is seen).
void append_wall(const SweepEdge& edge, const SweepInterval& interval, double range,
                 double max_chord_angle, Polygon& ring) {
  const double t_from = edge_parameter(edge, interval.from);
  const double t_to = edge_parameter(edge, interval.to);
  const Eigen::Vector2d d = edge.end - edge.start;
  if (t_to <= t_from) {  // a sliver of an interval, rounded to one point of the wall
    const Eigen::Vector2d p = edge.start + t_from * d;
    ring.push_back(p.norm() <= range ? p : Eigen::Vector2d(range * p.normalized()));
    return;
  }
  double disk0 = 0.0, disk1 = 0.0;
  const bool meets = disk_parameters(edge, range, disk0, disk1);
  const double t0 = std::max(t_from, disk0), t1 = std::min(t_to, disk1);
  if (!meets || t0 >= t1) {  // the wall lies beyond range (only for a finite range)
    append_arc(interval.from, interval_span(interval), range, max_chord_angle, ring);
    return;
  }
  const Eigen::Vector2d p0 = edge.start + t0 * d, p1 = edge.start + t1 * d;
  if (t0 > t_from) append_arc_between(interval.from, p0, range, max_chord_angle, ring);
  ring.push_back(p0);
  ring.push_back(p1);
  if (t1 < t_to) append_arc_between(p1, interval.to, range, max_chord_angle, ring);
}

/// The boundary of the seen region over one interval of the sweep.
void append_interval(const std::vector<SweepEdge>& edges, const SweepInterval& interval,
                     double range, double max_chord_angle, Polygon& ring) {
  const bool open = interval.edge < 0;
  if (open && std::isfinite(range)) {  // no wall within range
    append_arc(interval.from, interval_span(interval), range, max_chord_angle, ring);
  } else if (open || !edges[interval.edge].facing) {  // out of the area from its boundary
    ring.push_back(Eigen::Vector2d::Zero());
  } else {
    append_wall(edges[interval.edge], interval, range, max_chord_angle, ring);
  }
}

/// The ring without consecutive (cyclically) repeated vertices.
Polygon without_repeats(const Polygon& ring) {
  Polygon cleaned;
  for (const Eigen::Vector2d& p : ring) {
    if (cleaned.empty() || (p - cleaned.back()).norm() > kDuplicatePoint) cleaned.push_back(p);
  }
  while (cleaned.size() > 1 && (cleaned.back() - cleaned.front()).norm() <= kDuplicatePoint) {
    cleaned.pop_back();
  }
  return cleaned;
}

}  // namespace

Polygon visibility_polygon(const Area& area, const Eigen::Vector2d& viewpoint, double range,
                           int arc_segments) {
  if (arc_segments < 3) throw Error("visibility_polygon: arc_segments must be >= 3");
  const std::vector<SweepEdge> edges = edges_seen_from(area, viewpoint, 0.0, range);
  const double max_chord_angle = 2.0 * std::numbers::pi / arc_segments;
  Polygon ring;
  for (const SweepInterval& interval : sweep(edges)) {
    append_interval(edges, interval, range, max_chord_angle, ring);
  }
  Polygon world = without_repeats(ring);
  for (Eigen::Vector2d& p : world) p += viewpoint;
  return world;
}

}  // namespace gridloc
