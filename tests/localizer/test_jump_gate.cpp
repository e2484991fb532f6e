// Tests of engine/src/localizer/jump_gate.cpp: answers that follow the odometry pass, a jump
// is refused, a new place is accepted once it has held over the settling drive, and so is the
// first place from no prior (settle_first) unless a prior vouches for it.
#include "gridloc/engine/localizer/jump_gate.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace gridloc {
namespace {

GatedPose at(double x, double y, double odometry_x) {
  GatedPose answer;
  answer.pose = {x, y, 0.0};
  answer.covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal();
  answer.odometry = {odometry_x, 0.0, 0.0};
  return answer;
}

/// A gate whose first answer passes at once (the reference the tests measure from).
JumpGate first_passes(JumpGateOptions options = {}) {
  options.settle_first = false;
  return JumpGate(options);
}

TEST(JumpGate, AnswersThatFollowTheOdometryPass) {
  JumpGate gate = first_passes();
  EXPECT_TRUE(gate.admit(at(1.0, 1.0, 0.0)));  // the first answer is the reference
  EXPECT_TRUE(gate.admit(at(1.5, 1.0, 0.5)));
  EXPECT_TRUE(gate.admit(at(2.05, 1.02, 1.0)));  // within the odometry's error
}

TEST(JumpGate, AJumpIsRefusedUntilTheNewPlaceHasHeld) {
  JumpGateOptions options;
  options.settle_m = 1.0;
  options.settle_updates = 3;
  JumpGate gate = first_passes(options);
  EXPECT_TRUE(gate.admit(at(1.0, 1.0, 0.0)));
  EXPECT_FALSE(gate.admit(at(9.0, 1.0, 0.5)));  // 7.5 m off what the odometry says
  EXPECT_FALSE(gate.admit(at(9.5, 1.0, 1.0)));  // the new place holds: 0.5 m, 2 answers
  EXPECT_TRUE(gate.admit(at(10.0, 1.0, 1.5)));  // 1 m, 3 answers: accepted
  EXPECT_TRUE(gate.admit(at(10.5, 1.0, 2.0)));  // and now the reference
  EXPECT_FALSE(gate.admit(at(1.0, 1.0, 2.5)));  // going back is a jump again
}

TEST(JumpGate, AHeadingJumpIsRefused) {
  JumpGate gate = first_passes();
  EXPECT_TRUE(gate.admit(at(1.0, 1.0, 0.0)));
  GatedPose turned = at(1.0, 1.0, 0.0);
  turned.pose.theta = 0.3;  // 17 deg with no turn in the odometry
  EXPECT_FALSE(gate.admit(turned));
  gate.reset();
  EXPECT_TRUE(gate.admit(turned));
  JumpGateOptions bad;
  bad.settle_updates = 0;
  test::expect_error([&] { JumpGate broken(bad); }, {"settle_updates"});
  bad = {};
  bad.settle_first_updates = 0;
  test::expect_error([&] { JumpGate broken(bad); }, {"settle_first_updates"});
}

// settle_first (the default): the first place from no prior holds over the settling drive
// before it passes; standing still never settles it. A prior given as the reference vouches
// for an answer consistent with it, and one that contradicts it settles like a jump.
TEST(JumpGate, TheFirstPlaceSettlesUnlessAPriorVouchesForIt) {
  JumpGate gate;
  EXPECT_FALSE(gate.has_reference());
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(gate.admit(at(1.0, 1.0, 0.0))) << k;  // standing
  EXPECT_FALSE(gate.admit(at(1.5, 1.0, 0.5)));
  EXPECT_TRUE(gate.admit(at(2.0, 1.0, 1.0)));  // 1 m and 7 answers on the same place
  EXPECT_TRUE(gate.has_reference());
  JumpGate sparse;  // scans far apart: the first place and one 5 m on suffice
  EXPECT_FALSE(sparse.admit(at(1.0, 1.0, 0.0)));
  EXPECT_TRUE(sparse.admit(at(6.0, 1.0, 5.0)));
  JumpGate moved_away;  // the next answer elsewhere starts settling afresh
  EXPECT_FALSE(moved_away.admit(at(1.0, 1.0, 0.0)));
  EXPECT_FALSE(moved_away.admit(at(9.0, 1.0, 5.0)));
  JumpGate vouched;
  vouched.reset(at(1.0, 1.0, 0.0));
  EXPECT_TRUE(vouched.admit(at(1.02, 1.0, 0.0)));
  JumpGate contradicted;
  contradicted.reset(at(5.0, 1.0, 0.0));
  EXPECT_FALSE(contradicted.admit(at(1.0, 1.0, 0.0)));
}

}  // namespace
}  // namespace gridloc
