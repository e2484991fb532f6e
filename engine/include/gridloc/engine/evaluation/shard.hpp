#pragma once
/// Splitting an evaluation's trials across processes (issue 35): shard `index` of `count`
/// runs the trials whose number t has t % count == index, with exactly the inputs (starts,
/// seeds) the whole run would give them, so the shards' trials merged are the whole run's.
#include <string>

namespace gridloc {

struct Shard {
  int index = 0;  ///< 0-based; the command line's K/N is 1-based (index K - 1 of count N)
  int count = 1;

  /// Whether trial number `trial` (0-based) is this shard's.
  bool owns(int trial) const { return trial % count == index; }
  /// "K/N" (1-based), as the command line takes it.
  std::string to_string() const;
};

/// Throws gridloc::Error unless 1 <= count and 0 <= index < count.
void validate(const Shard& shard);

/// Parses "K/N" (1 <= K <= N, both integers; e.g. "2/8" or a job array's "$ID/8"); throws
/// gridloc::Error naming `option` and the text otherwise.
Shard parse_shard(const std::string& text, const std::string& option = "--shard");

}  // namespace gridloc
