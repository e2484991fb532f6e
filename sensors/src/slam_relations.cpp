#include "gridloc/sensors/slam_relations.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "text_lines.hpp"

namespace gridloc {

std::vector<SlamRelation> load_slam_relations(const std::string& path,
                                              const ResourceLimits& limits) {
  check_input_file(path, "relations file", limits);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the relations file");
  std::vector<SlamRelation> out;
  constexpr std::size_t kMaxLineBytes =
      std::size_t{64} * 1024;  // 8 numbers, and what may follow them
  detail::for_each_word_line(
      in, path, kMaxLineBytes, [&](const std::vector<std::string>& tokens, std::size_t line) {
        const std::string where = path + ":" + std::to_string(line);
        if (tokens.size() < 8) {
          throw Error(where + ": a relation needs 8 numbers (t1 t2 x y z roll pitch yaw), got " +
                      std::to_string(tokens.size()));
        }
        double v[8];
        for (std::size_t k = 0; k < 8; ++k) {
          const std::string& t = tokens[k];
          char* end = nullptr;
          v[k] = std::strtod(t.c_str(), &end);
          if (end != t.c_str() + t.size() || !std::isfinite(v[k])) {
            throw Error(where + ": field " + std::to_string(k + 1) + " is not a finite number: '" +
                        t + "'");
          }
        }
        out.push_back({v[0], v[1], Pose2{v[2], v[3], v[7]}, line});
        check_memory(static_cast<double>(out.capacity() * sizeof(SlamRelation)), limits,
                     path + ": the relations");
      });
  return out;
}

std::vector<RelationPair> pair_relations(const std::vector<SlamRelation>& relations,
                                         const CarmenLog& log, double offset_s,
                                         double tolerance_s) {
  // Scan indices sorted by time (a log's timestamps need not be in order).
  std::vector<std::size_t> order(log.lasers.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  auto time_of = [&](std::size_t k) { return log.lasers[k].timestamp + offset_s; };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return time_of(a) < time_of(b); });
  // The scan nearest to t, if within the tolerance.
  auto nearest = [&](double t, std::size_t& found) {
    const auto it = std::lower_bound(order.begin(), order.end(), t,
                                     [&](std::size_t k, double v) { return time_of(k) < v; });
    double best = std::numeric_limits<double>::infinity();
    bool ok = false;
    for (auto c : {it, it == order.begin() ? it : it - 1}) {
      if (c == order.end()) continue;
      // Within the tolerance, or within half the last printed digit of the scan's time.
      const double d = std::abs(time_of(*c) - t);
      const double allowed =
          std::max(tolerance_s, 0.5 * log.lasers[*c].timestamp_resolution + 1e-9);
      if (d <= allowed && d <= best) best = d, found = *c, ok = true;
    }
    return ok;
  };
  std::vector<RelationPair> pairs;
  for (const SlamRelation& r : relations) {
    RelationPair p{r, 0, 0};
    // Both ends on one scan (a coarse timestamp covering two relation times) say nothing of
    // the motion between them: dropped.
    if (nearest(r.t1, p.first) && nearest(r.t2, p.second) && p.first != p.second) {
      pairs.push_back(p);
    }
  }
  return pairs;
}

}  // namespace gridloc
