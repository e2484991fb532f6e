// Old spellings out of --help (old_spelling.hpp).
#include "old_spelling.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gridloc::cli {
namespace {

class WithoutOldSpellings : public CLI::Formatter {
 public:
  std::string make_group(std::string group, bool is_positional,
                         std::vector<const CLI::Option*> options) const override {
    if (group == kOldSpelling) return {};
    return CLI::Formatter::make_group(std::move(group), is_positional, std::move(options));
  }
};

}  // namespace

void hide_old_spellings(CLI::App* cmd) {
  cmd->formatter(std::make_shared<WithoutOldSpellings>());
}

}  // namespace gridloc::cli
