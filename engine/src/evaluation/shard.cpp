// Shards of an evaluation's trials: checking and parsing "K/N".
#include "gridloc/engine/evaluation/shard.hpp"

#include <charconv>
#include <system_error>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// The whole of `text` as a decimal int, or false.
bool parse_int(const std::string& text, int& value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return !text.empty() && error == std::errc() && stop == end;
}

}  // namespace

std::string Shard::to_string() const {
  return std::to_string(index + 1) + "/" + std::to_string(count);
}

void validate(const Shard& shard) {
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    throw Error("shard " + std::to_string(shard.index + 1) + " of " + std::to_string(shard.count) +
                ": needs 1 <= K <= N");
  }
}

Shard parse_shard(const std::string& text, const std::string& option) {
  const std::size_t slash = text.find('/');
  int k = 0, n = 0;
  if (slash == std::string::npos || !parse_int(text.substr(0, slash), k) ||
      !parse_int(text.substr(slash + 1), n) || n < 1 || k < 1 || k > n) {
    throw Error(option + " " + text + ": expected K/N with 1 <= K <= N (e.g. 2/8)");
  }
  return {k - 1, n};
}

}  // namespace gridloc
