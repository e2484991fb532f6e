// Seed 002 with the engine in the loop (issue 15): the truth is never ruled out, a twin
// the sensors cannot tell apart is never resolved, look-alikes that differ are.
#include "gridloc/engine/evaluation/engine_disambiguation.hpp"

#include <gtest/gtest.h>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"

namespace gridloc {
namespace {

EvalMap bundled(const std::string& name) {
  return {name, load_ros_map(std::string(GRIDLOC_TEST_MAPS_DIR) + "/" + name + ".yaml")};
}

SonarRing wheelchair() {
  return load_sonar_ring(std::string(GRIDLOC_TEST_MAPS_DIR) + "/sensors/wheelchair_14.yaml");
}

EngineDisambiguationOptions few_trials(int trials) {
  EngineDisambiguationOptions options;
  options.trials = trials;
  options.loop.planner.points = 40;
  return options;
}

TEST(EngineDisambiguation, TheSymmetricRoomsTwinStandsToTheEndAndIsNeverTakenForTheTruth) {
  const std::vector<EngineDisambiguationResult> results =
      run_engine_disambiguation({bundled("room_symmetric")}, wheelchair(), few_trials(3));
  ASSERT_EQ(results.size(), 1u);
  const EngineDisambiguationResult& room = results.front();
  EXPECT_EQ(room.trials, 3);
  EXPECT_EQ(room.truth_seeded, 3);
  EXPECT_EQ(room.true_survived_rate, 1.0);
  EXPECT_EQ(room.wrong_answers, 0);
  EXPECT_EQ(room.resolved_rate, 0.0);  // turned by 180 degrees the room is itself
}

TEST(EngineDisambiguation, TheApartmentsLookAlikesAreToldApartWithTheTruthKept) {
  const std::vector<EngineDisambiguationResult> results =
      run_engine_disambiguation({bundled("apartment_small")}, wheelchair(), few_trials(3));
  const EngineDisambiguationResult& apartment = results.front();
  EXPECT_EQ(apartment.trials, 3);
  EXPECT_EQ(apartment.true_survived_rate, 1.0);
  EXPECT_EQ(apartment.wrong_answers, 0);
  EXPECT_EQ(apartment.resolved_rate, 1.0);
}

TEST(EngineDisambiguation, BadOptionsAreRefused) {
  EngineDisambiguationOptions options = few_trials(0);
  EXPECT_THROW(validate(options), Error);
  options = few_trials(1);
  options.loop.elimination.drop_ratio = 1.5;
  EXPECT_THROW(validate(options), Error);
}

}  // namespace
}  // namespace gridloc
