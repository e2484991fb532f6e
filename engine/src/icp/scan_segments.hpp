#pragma once
// The segments of a scan and the matching points they give (seed 004 §3.2; internal).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "gridloc/engine/icp/robust_icp.hpp"

namespace gridloc::icp_detail {

/// Throws gridloc::Error unless `v` is positive and finite (names IcpOptions.`field`).
void check_positive(double v, const char* field);

/// The matching points of `current`: N_s per segment spread evenly along it.
std::vector<Eigen::Vector2d> matching_points(const std::vector<Eigen::Vector2d>& current,
                                             const IcpOptions& options, const char* who);

/// Each point's tangent normal from the total-least-squares line of its segment neighbours.
std::vector<Eigen::Vector2d> fitted_normals(const std::vector<Eigen::Vector2d>& points,
                                            const std::vector<Segment>& segments,
                                            std::size_t tangent_points);

}  // namespace gridloc::icp_detail
