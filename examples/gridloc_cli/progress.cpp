// Progress lines: `\r` on a terminal, one line per tenth otherwise.
#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace gridloc::cli {

std::function<void(int, int)> progress_line(const std::string& label, const std::string& what,
                                            bool quiet) {
  const bool terminal = isatty(fileno(stderr)) != 0;
  return [label, what, quiet, terminal, last = -1](int done, int total) mutable {
    if (quiet || total <= 0) return;
    const int tenth = 10 * done / total;
    if (terminal) {
      std::fprintf(stderr, "\r[%s] %d/%d %s", label.c_str(), done, total, what.c_str());
      if (done == total) std::fprintf(stderr, "\n");
    } else if (tenth != last) {
      std::fprintf(stderr, "[%s] %d/%d %s\n", label.c_str(), done, total, what.c_str());
    }
    last = tenth;
  };
}

}  // namespace gridloc::cli
