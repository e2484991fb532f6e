#pragma once
// Line-oriented text logs (internal to gridloc::sensors): the whitespace-separated words of
// each line, blank lines and '#' comments skipped, each line's length bounded.
#include <cstddef>
#include <functional>
#include <istream>
#include <sstream>
#include <string>
#include <vector>

#include "gridloc/grids/error.hpp"

namespace gridloc::detail {

/// Reads the next line of `in` into `text` (without its '\n'); false when nothing is left.
/// A line longer than `max_bytes` throws gridloc::Error naming `name` and the 1-based `line`
/// before more of it is kept: one line without an end cannot fill the memory.
inline bool read_bounded_line(std::istream& in, std::string& text, std::size_t max_bytes,
                              const std::string& name, std::size_t line) {
  text.clear();
  std::streambuf* buffer = in.rdbuf();
  bool any = false;
  for (int c = buffer->sbumpc(); c != std::char_traits<char>::eof(); c = buffer->sbumpc()) {
    any = true;
    if (c == '\n') return true;
    if (text.size() >= max_bytes) {
      throw Error(name + ":" + std::to_string(line) + ": a line longer than " +
                  std::to_string(max_bytes) + " bytes");
    }
    text.push_back(static_cast<char>(c));
  }
  in.setstate(std::ios::eofbit);
  return any;
}

/// Calls `visit(words, line)` for every line of `in` that holds words and is not a comment;
/// `line` is 1-based. Lines longer than `max_line_bytes` are errors (read_bounded_line).
inline void for_each_word_line(
    std::istream& in, const std::string& name, std::size_t max_line_bytes,
    const std::function<void(const std::vector<std::string>&, std::size_t)>& visit) {
  std::string text;
  for (std::size_t line = 1; read_bounded_line(in, text, max_line_bytes, name, line); ++line) {
    std::istringstream stream(text);
    std::vector<std::string> words;
    for (std::string w; stream >> w;) words.push_back(w);
    if (words.empty() || words[0][0] == '#') continue;
    visit(words, line);
  }
}

}  // namespace gridloc::detail
