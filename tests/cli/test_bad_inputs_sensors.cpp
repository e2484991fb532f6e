// The bad-input table (issue 14), sensors and the search: readings, rings, scans, logs and
// relations that are directories, devices, oversized or over the beam limit, and search
// options (steps, windows) whose grids or poses would take all the memory.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "bad_input_table.hpp"

namespace gridloc::test {
namespace {

/// A valid readings file of the bundled 14-sonar ring.
const std::pair<std::string, std::string> kReadings = {
    "readings.json",
    R"({"ranges_m": [0.9, 2.7, 4.1, 5.0, 2.6, 2.6, 1.4, 0.3, 0.3, 0.3, 0.3, 0.5, 0.5, 6.0]})"};

/// A valid CARMEN log: odometry and three 3-beam laser scans.
const std::pair<std::string, std::string> kLog = {"small.log",
                                                  "ODOM 1 1 0 0 0 0 1.0 h 1.0\n"
                                                  "FLASER 3 1.0 2.5 3.0 1 1 0 1 1 0 1.5 h 1.5\n"
                                                  "FLASER 3 1.0 2.5 3.0 1 1 0 1 1 0 2.5 h 2.5\n"
                                                  "FLASER 3 1.0 2.5 3.0 1 1 0 1 1 0 3.5 h 3.5\n"};

/// Writes `lines` lines of `line` to `name` in the folder (large files are made, not held).
std::function<void(const TempDir&)> repeated(const std::string& name, const std::string& head,
                                             const std::string& line, long lines,
                                             const std::string& tail) {
  return [=](const TempDir& dir) {
    std::ofstream out(dir.file(name), std::ios::binary);
    out << head;
    for (long k = 0; k < lines; ++k) out << line;
    out << tail;
  };
}

const std::string kLocalize = "localize --map {maps}/room_rect.yaml ";

const std::vector<BadInputCase> kSensorCases = {
    // Case 1: directories, devices and large files, named where they enter.
    {"ReadingsDirectory",
     {},
     kLocalize + "--global --readings {dir}",
     {"is a directory", "readings file"}},
    {"RingDirectory",
     {kReadings},
     kLocalize + "--global --readings {dir}/readings.json --ring {dir}",
     {"is a directory", "sonar ring file"}},
    {"ScanDirectory", {}, kLocalize + "--global --scan {dir}", {"is a directory", "scan file"}},
    {"ReadingsDevice",
     {},
     kLocalize + "--global --readings /dev/zero",
     {"/dev/zero", "not a regular file"}},
    {"LogDirectory",
     {},
     "map-from-log --log {dir} --out {dir}/m.yaml",
     {"is a directory", "CARMEN log"}},
    {"TrackLogDirectory",
     {},
     "track --map {maps}/room_rect.yaml --log {dir} --prior 1,1,0",
     {"is a directory", "CARMEN log"}},
    {"RelationsDirectory",
     {kLog},
     "relations --log {dir}/small.log --relations {dir}",
     {"is a directory", "relations file"}},
    {"ReadingsOverFileLimit",
     {},
     "--max-file-mb 1 " + kLocalize + "--global --readings {dir}/big.json",
     {"big.json", "--max-file-mb"},
     repeated("big.json", R"({"pad": ")", "0123456789abcdef", 140000, R"("})")},
    {"LogOverFileLimit",
     {},
     "map-from-log --max-file-mb 1 --log {dir}/big.log --out {dir}/m.yaml",
     {"big.log", "--max-file-mb"},
     repeated("big.log", "", "# a comment line of a large log\n", 70000, "")},
    // Case 2: beams counted while reading.
    {"MillionBeamScan",
     {},
     kLocalize + "--global --scan {dir}/huge.csv",
     {"huge.csv:100001", "--max-beams"},
     repeated("huge.csv", "", "0.5,1.5\n", 1000000, "")},
    {"ReadingsOverBeamLimit",
     {},
     kLocalize + "--global --readings {dir}/many.json",
     {"many.json", "--max-beams"},
     repeated("many.json", R"({"ranges_m": [1)", ",1", 200000, "]}")},
    {"LogDeclaresABillionBeams",
     {{"huge.log", "FLASER 1000000000 1 2 3\n"}},
     "map-from-log --log {dir}/huge.log --out {dir}/m.yaml",
     {"huge.log:1", "reading count", "--max-beams"}},
    {"RingOverBeamLimit",
     {},
     "--max-beams 10 simulate --map {maps}/room_rect.yaml --pose 2,1.5,0",
     {"wheelchair_14.yaml", "14 sonars", "--max-beams"}},
    {"ReadingsOfARingOverBeamLimit",
     {kReadings},
     "--max-beams 10 " + kLocalize + "--global --readings {dir}/readings.json",
     {"readings.json", "11 values", "--max-beams"}},
    // Case 3: the search's grids and poses, estimated before they are allocated.
    {"StepXyTenthOfAMillimetre",
     {kReadings},
     kLocalize + "--readings {dir}/readings.json --prior 2,1.5,0 --step-xy 1e-4",
     {"global grid at 0.0001 m", "--max-cells"}},
    {"StepXyGlobalOverMemory",
     {kReadings},
     kLocalize + "--readings {dir}/readings.json --global --step-xy 4e-3 --max-memory-mb 1000",
     {"would need about", "--max-memory-mb"}},
    {"StepThetaNanoRadian",
     {kReadings},
     kLocalize + "--readings {dir}/readings.json --global --step-theta 1e-9",
     {"step_theta", "headings"}},
    {"HeatmapVolumeOverMemory",
     {kReadings},
     "--max-memory-mb 100 heatmap --map {maps}/room_rect.yaml --readings {dir}/readings.json "
     "--prior 2,1.5,0 --window-theta 3.14 --step-theta 1e-4 --out {dir}/hm",
     {"headings", "--max-memory-mb"}},
    // Case 4: the Localizer's estimator goes through the same estimate.
    {"TrackOverMemory",
     {kLog},
     "track --max-memory-mb 1 --map {maps}/room_rect.yaml --log {dir}/small.log --prior 1,1,0",
     {"correlation estimator", "--max-memory-mb"}},
    // Issue 14, case 7: said "simulate: pose ... lies outside the map".
    {"StepXyCoarserThanTheMap",
     {kReadings},
     kLocalize + "--readings {dir}/readings.json --global --step-xy 1e3",
     {"resolution 1000 m", "--step-xy", "coarser than the map"}},
    {"OneCellMapGlobal",
     {kReadings,
      {"one.yaml",
       "image: one.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
       "occupied_thresh: 0.65\nfree_thresh: 0.196\n"},
      {"one.pgm", std::string("P5\n1 1\n255\n\xfe", 12)}},
     "localize --map {dir}/one.yaml --readings {dir}/readings.json --global",
     {"coarser than the map (0.05 x 0.05 m)"}},
    // Case 5: found by the table of bad numbers (SIGSEGV before).
    {"ArcDeeperThanTheCanvas",
     {kReadings},
     kLocalize + "--readings {dir}/readings.json --prior 2,1.5,0 --arc-depth 99999999999",
     {"arc depth must lie in [0, 2] cells"}},
    {"HeatmapStepThetaHuge",  // drew for minutes before
     {kReadings},
     "heatmap --map {maps}/room_rect.yaml --readings {dir}/readings.json --prior 2,1.5,0 "
     "--step-theta 1e300 --out {dir}/hm",
     {"step_theta", "(0, 2 pi]"}},
    {"TrackNegativeResolution",  // fell back to the map's cell silently
     {kLog},
     "track --map {maps}/room_rect.yaml --log {dir}/small.log --prior 1,1,0 --resolution -1",
     {"--resolution", "got -1"}},
    {"MapFromLogTooFine",
     {kLog},
     "map-from-log --log {dir}/small.log --out {dir}/m.yaml --resolution 1e-5",
     {"map from log", "--max-cells"}},
};

class BadInputSensors : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(BadInputSensors, ExitsTwoWithOneLine) {
  run_bad_input(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Table, BadInputSensors, ::testing::ValuesIn(kSensorCases), BadInputName{});

}  // namespace
}  // namespace gridloc::test
