#pragma once
// gridloc relations --plot (issue 30): the worst pairs for a person to look at, one panel
// each: the reference scan, the current scan at the relation's motion and at the answer, the
// answer's 2-sigma ellipse, and what the pair's row says.
#include <Eigen/Core>
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "gridloc/engine/evaluation/relations.hpp"

namespace gridloc::cli {

struct RelationPanel {
  std::vector<Eigen::Vector2d> reference;  ///< the reference scan's returns, its frame
  std::vector<Eigen::Vector2d> current;    ///< the current scan's returns, its own frame
  RelationTrial trial;
};

struct RelationsPicture {
  std::vector<RelationPanel> panels;
  std::string title, caption;
};

/// The trials to draw, at most `count`: failures first, each group by its error (the
/// translation error plus 1 cm per degree), largest first.
std::vector<std::size_t> worst_trials(const std::vector<RelationTrial>& trials, std::size_t count);

/// The picture, three panels to a row; gridloc::Error for no panel.
cv::Mat render_relations(const RelationsPicture& picture);

}  // namespace gridloc::cli
