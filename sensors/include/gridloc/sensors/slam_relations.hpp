#pragma once
/// Ground-truth relations of the SLAM benchmark (Kümmerle et al. 2009): one line per relation,
/// `t1 t2 x y z roll pitch yaw`, the pose of the robot at time t2 in its frame at time t1.
/// Matched to the scans of a CARMEN log by timestamp.
#include <string>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/sensors/carmen_log.hpp"

namespace gridloc {

struct SlamRelation {
  double t1 = 0.0, t2 = 0.0;  ///< absolute times (s)
  Pose2 motion;               ///< the robot at t2 in the frame at t1 (x, y, yaw)
  std::size_t line = 0;
};

/// Reads a relations file; throws gridloc::Error naming the line for fewer than 8 numbers,
/// a field that is not a number or not finite, a line over 64 KiB, and for a missing file, a
/// directory or device, a file over limits.max_file_mb or relations over
/// limits.max_memory_mb.
std::vector<SlamRelation> load_slam_relations(const std::string& path,
                                              const ResourceLimits& limits = {});

/// A relation whose two times fall on scans of a log.
struct RelationPair {
  SlamRelation relation;
  std::size_t first = 0;   ///< index into CarmenLog::lasers of the scan at t1
  std::size_t second = 0;  ///< ... and at t2
};

/// The relations whose t1 and t2 both lie within `tolerance_s` (or half the unit of the last
/// digit the log printed, when coarser) of a scan's timestamp plus `offset_s` (relations use
/// absolute time, some logs relative time: Intel's offset is 976052857.337311 s), with the
/// nearest scans. A relation whose two ends fall on the same scan is left out.
std::vector<RelationPair> pair_relations(const std::vector<SlamRelation>& relations,
                                         const CarmenLog& log, double offset_s,
                                         double tolerance_s = 0.002);

}  // namespace gridloc
