#pragma once
/// Splitting a log's laser scans into a part that draws a map and a held-out part that is
/// localized against it, so that no scan is matched against a map drawn from itself (issue
/// 13's real-data evaluation).
#include <cstddef>
#include <string>
#include <vector>

#include "gridloc/sensors/carmen_log.hpp"

namespace gridloc {

/// How a log was cut into blocks.
enum class SplitRule {
  All,         ///< no split: every scan in the map part
  TimeBlocks,  ///< blocks of LogSplitOptions::block_s seconds
  ScanBlocks,  ///< blocks of LogSplitOptions::block_scans consecutive scans
};

/// The rule's name, as the command line prints it: "all", "time blocks", "scan blocks".
std::string to_string(SplitRule rule);

struct LogSplitOptions {
  /// Block length (s) when the timestamps are usable: a robot driving at 0.3-0.5 m/s covers
  /// 10-15 m in 30 s, so each block sees a stretch of the building that the next one revisits.
  double block_s = 30.0;
  /// Block length (scans) when they are not (all-zero, garbage or coarse timestamps): about
  /// 30 s of the acschaefer_ple logs with usable times, which keep a scan every 1.5-5 s of
  /// driving (6-19 scans per 30 s; freiburg-079 135).
  int block_scans = 10;
  /// Timestamps may step back by this much (s) and still be usable: the Intel log's come up
  /// to 0.86 s early now and then. A scan stepping back belongs to its predecessor's block.
  double max_backstep_s = 1.0;
};

/// Checks `options`; throws gridloc::Error naming the field.
void validate(const LogSplitOptions& options);

/// The two parts of a log, as indices into its laser records, each in log order.
struct LogSplit {
  SplitRule rule = SplitRule::All;
  std::vector<std::size_t> map;       ///< the even blocks (0, 2, ...): draw the map from these
  std::vector<std::size_t> held_out;  ///< the odd blocks: localize these
  std::size_t blocks = 0;             ///< blocks holding at least one scan
  /// Why the timestamps were not used (ScanBlocks), or "".
  std::string timestamps_unusable;
};

/// Why `lasers`' timestamps cannot cut blocks of options.block_s, or "" when they can: they
/// must be finite, printed finer than a tenth of a block (LaserRecord::timestamp_resolution),
/// never step back by more than options.max_backstep_s, and span more than one block (and
/// fewer than 1e12 blocks).
std::string timestamp_problem(const std::vector<LaserRecord>& lasers,
                              const LogSplitOptions& options = {});

/// Alternate blocks of `lasers`: by time when timestamp_problem finds nothing (a scan's block
/// is counted from the first timestamp, using the latest timestamp so far, so blocks are runs
/// of consecutive scans), else by count. Throws gridloc::Error for no scan or bad options.
LogSplit split_log(const std::vector<LaserRecord>& lasers, const LogSplitOptions& options = {});

/// Every scan of `lasers` in the map part (SplitRule::All, one block). Throws gridloc::Error for
/// no scan.
LogSplit all_scans(const std::vector<LaserRecord>& lasers);

}  // namespace gridloc
