#include "gridloc/sensors/log_split.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"

namespace gridloc {
namespace {

void require_scans(const std::vector<LaserRecord>& lasers) {
  if (lasers.empty()) throw Error("log split: the log holds no laser scan");
}

/// A number as the messages print it ("30", "0.86", "4.29497e+09").

/// Puts scan k of block `block` into its part, counting the blocks that hold a scan.
void assign(LogSplit& split, std::size_t k, long long block, long long& last_block) {
  (block % 2 == 0 ? split.map : split.held_out).push_back(k);
  if (block != last_block) ++split.blocks;
  last_block = block;
}

LogSplit time_blocks(const std::vector<LaserRecord>& lasers, double block_s) {
  LogSplit split;
  split.rule = SplitRule::TimeBlocks;
  const double start = lasers.front().timestamp;
  double latest = start;
  long long last_block = -1;
  for (std::size_t k = 0; k < lasers.size(); ++k) {
    latest = std::max(latest, lasers[k].timestamp);
    assign(split, k, static_cast<long long>(std::floor((latest - start) / block_s)), last_block);
  }
  return split;
}

LogSplit scan_blocks(const std::vector<LaserRecord>& lasers, int block_scans) {
  LogSplit split;
  split.rule = SplitRule::ScanBlocks;
  long long last_block = -1;
  for (std::size_t k = 0; k < lasers.size(); ++k) {
    assign(split, k, static_cast<long long>(k / static_cast<std::size_t>(block_scans)), last_block);
  }
  return split;
}

}  // namespace

std::string to_string(SplitRule rule) {
  switch (rule) {
    case SplitRule::All:
      return "all";
    case SplitRule::TimeBlocks:
      return "time blocks";
    case SplitRule::ScanBlocks:
      return "scan blocks";
  }
  return "?";
}

void validate(const LogSplitOptions& options) {
  if (!(options.block_s > 0.0) || !std::isfinite(options.block_s)) {
    throw Error("log split: block_s must be > 0 and finite, got " +
                message_number(options.block_s));
  }
  if (options.block_scans < 1) {
    throw Error("log split: block_scans must be >= 1, got " + std::to_string(options.block_scans));
  }
  if (!(options.max_backstep_s >= 0.0) || !std::isfinite(options.max_backstep_s)) {
    throw Error("log split: max_backstep_s must be >= 0 and finite, got " +
                message_number(options.max_backstep_s));
  }
}

std::string timestamp_problem(const std::vector<LaserRecord>& lasers,
                              const LogSplitOptions& options) {
  double latest = lasers.empty() ? 0.0 : lasers.front().timestamp;
  for (const LaserRecord& r : lasers) {
    const std::string where = "line " + std::to_string(r.line) + "'s timestamp ";
    if (!std::isfinite(r.timestamp)) return where + "is not finite";
    if (r.timestamp_resolution > 0.1 * options.block_s) {
      return where + message_number(r.timestamp) + " is printed to " +
             message_number(r.timestamp_resolution) + " s only";
    }
    if (r.timestamp < latest - options.max_backstep_s) {
      return where + message_number(r.timestamp) + " steps back from " + message_number(latest);
    }
    latest = std::max(latest, r.timestamp);
  }
  const double span = lasers.empty() ? 0.0 : latest - lasers.front().timestamp;
  if (!(span > options.block_s)) {
    return "the timestamps span " + message_number(span) + " s, not more than one block";
  }
  if (span / options.block_s > 1e12) return "the timestamps span " + message_number(span) + " s";
  return "";
}

LogSplit split_log(const std::vector<LaserRecord>& lasers, const LogSplitOptions& options) {
  validate(options);
  require_scans(lasers);
  const std::string problem = timestamp_problem(lasers, options);
  if (problem.empty()) return time_blocks(lasers, options.block_s);
  LogSplit split = scan_blocks(lasers, options.block_scans);
  split.timestamps_unusable = problem;
  return split;
}

LogSplit all_scans(const std::vector<LaserRecord>& lasers) {
  require_scans(lasers);
  LogSplit split;
  split.blocks = 1;
  split.map.resize(lasers.size());
  for (std::size_t k = 0; k < lasers.size(); ++k) split.map[k] = k;
  return split;
}

}  // namespace gridloc
