#pragma once
/// Progress on standard error for long runs: on a terminal one line rewritten with `\r`;
/// otherwise (a log file, CI) a line at each tenth, so logs stay readable.
#include <functional>
#include <string>

namespace gridloc::cli {

/// A callback (done, total) printing "[label] done/total what"; nothing when `quiet`.
std::function<void(int, int)> progress_line(const std::string& label, const std::string& what,
                                            bool quiet);

}  // namespace gridloc::cli
