#pragma once
// Line-oriented text logs (internal to gridloc::sensors): the whitespace-separated words of
// each line, blank lines and '#' comments skipped.
#include <cstddef>
#include <functional>
#include <istream>
#include <sstream>
#include <string>
#include <vector>

namespace gridloc::detail {

/// Calls `visit(words, line)` for every line of `in` that holds words and is not a comment;
/// `line` is 1-based.
inline void for_each_word_line(
    std::istream& in,
    const std::function<void(const std::vector<std::string>&, std::size_t)>& visit) {
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    std::istringstream stream(text);
    std::vector<std::string> words;
    for (std::string w; stream >> w;) words.push_back(w);
    if (words.empty() || words[0][0] == '#') continue;
    visit(words, line);
  }
}

}  // namespace gridloc::detail
