// Which links to localize along (seed 003 ch. IV A): the shortest maximum link.
#include <algorithm>
#include <numeric>

#include "gridloc/engine/team/team_localization.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {

namespace {

int find_root(std::vector<int>& parent, int robot) {
  while (parent[robot] != robot) robot = parent[robot] = parent[parent[robot]];
  return robot;
}

/// Kruskal's tree: a minimum spanning tree also minimizes its longest link.
std::vector<int> spanning_tree(int robots, const std::vector<VirtualLink>& links) {
  std::vector<int> order(links.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return links[a].length_m < links[b].length_m; });
  std::vector<int> parent(robots);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> tree;
  for (int l : order) {
    const int a = find_root(parent, links[l].from), b = find_root(parent, links[l].to);
    if (a == b) continue;
    parent[a] = b;
    tree.push_back(l);
  }
  for (int r = 1; r < robots; ++r)
    if (find_root(parent, r) != find_root(parent, 0))
      throw Error("robot " + std::to_string(r) +
                  " has no link to robot 0's group: no pair of robots within the camera's "
                  "range with a line of sight joins them");
  return tree;
}

}  // namespace

std::vector<int> choose_links(int robots, const std::vector<VirtualLink>& links) {
  if (robots < 1) throw Error("a team needs at least one robot");
  std::vector<int> tree = spanning_tree(robots, links);  // shortest first
  std::vector<int> ordered;
  std::vector<bool> placed(robots, false);
  while (!tree.empty()) {
    auto next = std::find_if(tree.begin(), tree.end(), [&](int l) {
      return ordered.empty() || placed[links[l].from] != placed[links[l].to];
    });
    placed[links[*next].from] = placed[links[*next].to] = true;
    ordered.push_back(*next);
    tree.erase(next);
  }
  return ordered;
}

}  // namespace gridloc
