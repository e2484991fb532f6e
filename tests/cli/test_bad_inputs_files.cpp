// The bad-input table (issue 14), input files: missing, directories, devices, oversized.
#include <gtest/gtest.h>

#include <vector>

#include "bad_input_table.hpp"

namespace gridloc::test {
namespace {

/// A valid readings file of the bundled 14-sonar ring, for cases about other inputs.
const std::pair<std::string, std::string> kReadings = {
    "readings.json",
    R"({"ranges_m": [0.9, 2.7, 4.1, 5.0, 2.6, 2.6, 1.4, 0.3, 0.3, 0.3, 0.3, 0.5, 0.5, 6.0]})"};

const std::vector<BadInputCase> kFileCases = {
    {"MissingMap",
     {kReadings},
     "localize --global --map {dir}/none.yaml --readings {dir}/readings.json",
     {"none.yaml", "not found"}},
    {"FileLimitIsChecked", {}, "--max-file-mb 0 demo", {"--max-file-mb", "positive"}},
};

class BadInputFiles : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(BadInputFiles, ExitsTwoWithOneLine) {
  run_bad_input(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Table, BadInputFiles, ::testing::ValuesIn(kFileCases), BadInputName{});

}  // namespace
}  // namespace gridloc::test
