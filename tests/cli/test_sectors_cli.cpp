// End-to-end tests of the visibility sectors in the gridloc tool: `localize --estimator
// sectors`, `eval` on polygon maps, and `gridloc sectors` (seed 000).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "gridloc/engine/sectors/visibility_sectors.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace test;
using Cli = CliTest;

TEST_F(Cli, LocalizeWithVisibilitySectors) {
  // The L-shaped room as a polygon map and a noise-free 360-beam scan from (1.2, 1.6, 0.7).
  const std::string poly =
      dir.write("l.yaml", "boundary: [[0, 0], [7, 0], [7, 3], [3, 3], [3, 6], [0, 6], [0, 0]]\n");
  const PolygonMap m = load_polygon_map(poly);
  const Pose2 truth{1.2, 1.6, 0.7};
  const std::string scan = write_scan_csv(dir, "l.csv", polygon_scan(m, truth, 360, 20.0));
  const CliRun r = run_cli(dir, "localize --map " + quote(poly) + " --scan " + quote(scan) +
                                    " --max-range 20 --global --estimator sectors");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("estimator"), "sectors");
  EXPECT_EQ(j.at("verdict"), "localized") << r.out;
  EXPECT_LE(std::hypot(j.at("pose").at("x").get<double>() - truth.x,
                       j.at("pose").at("y").get<double>() - truth.y),
            0.02)
      << r.out;
  expect_cli_error(run_cli(dir, "localize --map " + quote(test::map_path("room_l")) + " --scan " +
                                    quote(scan) + " --max-range 20 --global --estimator sectors"),
                   "polygon map");
  // The fix refined by the local correlation search: the same verdict, a pose as close.
  const CliRun refined =
      run_cli(dir, "localize --map " + quote(poly) + " --scan " + quote(scan) +
                       " --max-range 20 --global --estimator sectors+correlation");
  ASSERT_EQ(refined.status, 0) << refined.err;
  const auto k = nlohmann::json::parse(refined.out);
  EXPECT_EQ(k.at("estimator"), "sectors+correlation");
  EXPECT_EQ(k.at("verdict"), "localized") << refined.out;
  EXPECT_LE(std::hypot(k.at("pose").at("x").get<double>() - truth.x,
                       k.at("pose").at("y").get<double>() - truth.y),
            0.03)
      << refined.out;
}

TEST_F(Cli, EvalOnPolygonMapsComparesSectorsAndCorrelation) {
  // The sector protocol: the same global trials for every estimator, the contract's fields.
  const CliRun r = run_cli(dir,
                           "eval --estimator sectors,correlation --maps polygons/room_l "
                           "--trials 4 --json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("protocol"), "sectors");
  EXPECT_EQ(j.at("trials"), 4);
  EXPECT_TRUE(j.at("prior").is_null());
  ASSERT_EQ(j.at("configurations").size(), 2u);
  EXPECT_EQ(j.at("configurations")[0].at("estimator"), "sectors");
  EXPECT_EQ(j.at("configurations")[1].at("estimator"), "correlation");
  for (const auto& c : j.at("configurations")) {
    const double id = c.at("sector_identification_rate");
    EXPECT_GE(id, 0.0);
    EXPECT_LE(id, 1.0);
    EXPECT_GE(c.at("successes").get<int>(), 3) << c.dump();  // measured: 4 and 4
    EXPECT_EQ(c.at("localized").get<int>() + c.at("ambiguous").get<int>() +
                  c.at("not_localized").get<int>(),
              4);
  }
  // A sector estimator alone defaults to the bundled polygon maps; --trials-out writes a row
  // per trial and estimator.
  const std::string csv = dir.file("trials.csv");
  const CliRun t =
      run_cli(dir, "eval --estimator sectors --trials 1 --quiet --trials-out " + quote(csv));
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_NE(t.out.find("office.yaml"), std::string::npos) << t.out;
  EXPECT_EQ(lines(read_file(csv)).size(), 5u);  // the header and 4 maps
  // The seed 001 protocol names the field too, null.
  const CliRun s = run_cli(dir, "eval --maps room_rect --trials 1 --json --quiet");
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_TRUE(nlohmann::json::parse(s.out)
                  .at("configurations")[0]
                  .at("sector_identification_rate")
                  .is_null());
}

TEST_F(Cli, EvalSectorProtocolErrors) {
  expect_cli_error(run_cli(dir, "eval --estimator sectors --maps room_l --trials 1"),
                   {"polygon maps"});
  expect_cli_error(run_cli(dir, "eval --maps polygons/room_l,room_l --trials 1"), {"mixes"});
  expect_cli_error(run_cli(dir, "eval --maps polygons/room_l --noisy --trials 1"), {"--noisy"});
  expect_cli_error(run_cli(dir, "eval --estimator icp --maps polygons/room_l --trials 1"),
                   {"icp", "prior"});
  expect_cli_error(run_cli(dir, "eval --estimator sectors --laser-beams 10 --trials 1"), {"beams"});
  expect_cli_error(run_cli(dir, "eval --estimator sectors --maps polygons/nowhere --trials 1"),
                   {"nowhere.yaml"});
}

TEST_F(Cli, SectorsOfARectangle) {
  // A plain rectangle is one sector: its four corners M and its four walls, seen square on, m,
  // from east counter-clockwise. (maps/polygons/room_rect.yaml is not plain: its desk and
  // cupboard notches cut it into many sectors, see the next test.)
  const std::string rect =
      dir.write("rect.yaml", "boundary: [[0, 0], [6, 0], [6, 4], [0, 4], [0, 0]]\n");
  const CliRun r = run_cli(dir, "sectors --polygons " + quote(rect) + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("polygons").get<std::string>(), rect);
  ASSERT_EQ(j.at("sector_count").get<int>(), 1);
  ASSERT_EQ(j.at("sectors").size(), 1u);
  EXPECT_EQ(j.at("ambiguous_count").get<int>(), 0);
  const auto& s = j.at("sectors")[0];
  EXPECT_EQ(s.at("id").get<int>(), 1);
  EXPECT_EQ(s.at("label").get<std::string>(), "mMmMmMmM");
  EXPECT_FALSE(s.at("ambiguous").get<bool>());
  EXPECT_NEAR(s.at("area_m2").get<double>(), 24.0, 1e-9);
  EXPECT_EQ(s.at("visible_vertices").size(), 4u);
  const double x = s.at("representative").at("x"), y = s.at("representative").at("y");
  EXPECT_TRUE(x > 0.0 && x < 6.0 && y > 0.0 && y < 4.0) << s.dump();
  // Eqs. (10)-(11): 3 readings per edge need more than 2.
  EXPECT_GT(s.at("n_min").get<int>(), s.at("n_min_two").get<int>());
  EXPECT_GT(s.at("n_min_two").get<int>(), 0);
  EXPECT_EQ(j.at("n_min_two"), s.at("n_min_two"));

  // The table: a title line, the header, one row per sector, the summary.
  const CliRun t = run_cli(dir, "sectors --polygons " + quote(rect));
  ASSERT_EQ(t.status, 0) << t.err;
  const auto l = lines(t.out);
  ASSERT_EQ(l.size(), 4u) << t.out;
  EXPECT_NE(l[1].find("Label"), std::string::npos) << l[1];
  EXPECT_NE(l[2].find("mMmMmMmM"), std::string::npos) << l[2];
  EXPECT_NE(l[2].find("24.00"), std::string::npos) << l[2];
  EXPECT_NE(l[3].find("1 sector, 0 ambiguous"), std::string::npos) << l[3];
}

// The bundled bare L prints the table engine/doc/sectors.md shows.
TEST_F(Cli, SectorsOfTheBundledBareLAreTheDocsTable) {
  const CliRun r =
      run_cli(dir, "sectors --polygons " + quote(test::maps_dir() + "/polygons/l_bare.yaml"));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* row : {"   1  mMmMmMmMmM      9.00  (1.48, 1.48)", "   2  mMmDcMmMmM      4.49",
                          "   3  mMmDcmMmM       7.51", "   4  mMmMmMmMcD      3.38",
                          "   5  mMmMmMmcD       5.62", "5 sectors, 0 ambiguous"}) {
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  }
}

TEST_F(Cli, SectorsMatchComputeSectors) {
  // The hand-derived L of test_visibility_sectors.cpp: the reflex corner's five sectors.
  const std::string l_room =
      dir.write("l.yaml", "boundary: [[0, 0], [7, 0], [7, 3], [3, 3], [3, 6], [0, 6], [0, 0]]\n");
  // And the bundled maps, obstacles and notches included: the command reports what
  // compute_sectors() finds, sector for sector.
  for (const std::string& file : {l_room, test::maps_dir() + "/polygons/room_l.yaml",
                                  test::maps_dir() + "/polygons/room_rect.yaml"}) {
    const CliRun r = run_cli(dir, "sectors --polygons " + quote(file) + " --json");
    ASSERT_EQ(r.status, 0) << file << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const SectorMap s = compute_sectors(load_polygon_map(file));
    ASSERT_EQ(j.at("sector_count").get<std::size_t>(), s.sectors.size()) << file;
    ASSERT_EQ(j.at("sectors").size(), s.sectors.size()) << file;
    int ambiguous = 0;
    for (std::size_t k = 0; k < s.sectors.size(); ++k) {
      const auto& js = j.at("sectors")[k];
      EXPECT_EQ(js.at("id").get<std::size_t>(), k + 1);
      EXPECT_EQ(js.at("label").get<std::string>(), s.sectors[k].label) << file << " " << k;
      EXPECT_EQ(js.at("ambiguous").get<bool>(), s.sectors[k].ambiguous) << file << " " << k;
      EXPECT_EQ(js.at("visible_vertices").size(), s.sectors[k].visible.size());
      ambiguous += s.sectors[k].ambiguous ? 1 : 0;
    }
    EXPECT_EQ(j.at("ambiguous_count").get<int>(), ambiguous) << file;
    EXPECT_EQ(j.at("n_min_two").get<int>(), s.n_min_two()) << file;
    if (file == l_room) {
      EXPECT_EQ(s.sectors.size(), 5u);
    } else {
      EXPECT_GT(s.sectors.size(), 5u) << file << ": its notches and obstacles cut it further";
    }
  }
}

TEST_F(Cli, SectorsErrors) {
  const std::string missing = dir.file("no_such_room.yaml");
  expect_cli_error(run_cli(dir, "sectors --polygons " + quote(missing)), {"no_such_room.yaml"});
  expect_cli_error(run_cli(dir, "sectors --polygons " + quote(missing) + " --json"),
                   {"no_such_room.yaml"});
  expect_cli_error(run_cli(dir, "sectors"), {"--polygons"});
  const std::string rect =
      dir.write("rect.yaml", "boundary: [[0, 0], [6, 0], [6, 4], [0, 4], [0, 0]]\n");
  expect_cli_error(run_cli(dir, "sectors --polygons " + quote(rect) + " --cell 0"), {"--cell"});
  const std::string open = dir.write("open.yaml", "boundary: [[0, 0], [4, 0], [4, 3], [0, 3]]\n");
  expect_cli_error(run_cli(dir, "sectors --polygons " + quote(open)), {"open.yaml", "not closed"});
  // An --out that cannot be a folder (a file is in the way) is named.
  const std::string file = dir.write("a_file", "x");
  const std::string out = file + "/sectors";
  expect_cli_error(run_cli(dir, "sectors --polygons " + quote(rect) + " --out " + quote(out)),
                   {"--out", out});
}

}  // namespace
}  // namespace gridloc
