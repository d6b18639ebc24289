// Friction at either shaft (issue #23 item 3): at the wave generator the law sees omega1 and
// loads the input; at the output bearing it sees omega2 and adds to the output's load, as the
// simulated bench's plant applies it.
#include <gtest/gtest.h>

#include "gear_test_support.hpp"

namespace wavebench::model {
namespace {

TEST(FrictionSide, OutputFrictionSeesTheOutputSpeedAndLoadsTheOutput) {
  const double omega1 = 10.0;
  const CoulombStribeckFriction f{0.4, 0.5, 0.01, 1e-3, 1e-3};
  const CoulombStribeck law(f);
  for (const auto side : {FrictionSide::kInput, FrictionSide::kOutput}) {
    GearParams p = testing::bare_gear(100, 1e-4, 0.05, 3e4);
    p.friction = f;
    p.friction_side = side;
    p.input = KinematicInput{omega1, 0, {}, {}};
    p.load.output_torque.offset = 2.0;
    const GearModel model(p);
    std::vector<double> y = model.initial_state();
    const std::vector<double> d = model.initial_discrete();
    const GearOutputs o = model.outputs(0.0, y, d);
    const double omega2 = o.omega2;
    EXPECT_NEAR(omega2, omega1 / 100, 1e-12);
    if (side == FrictionSide::kOutput) {
      EXPECT_DOUBLE_EQ(o.friction_torque, law.torque(omega2));
      EXPECT_DOUBLE_EQ(o.load_torque, 2.0 + law.torque(omega2));
      // The input carries no friction: the motor holds the kinematic motion against the mesh.
      EXPECT_NEAR(o.motor_torque, o.gear_torque / 100, 1e-12);
    } else {
      EXPECT_DOUBLE_EQ(o.friction_torque, law.torque(omega1));
      EXPECT_DOUBLE_EQ(o.load_torque, 2.0);
      EXPECT_NEAR(o.motor_torque, o.gear_torque / 100 + law.torque(omega1), 1e-12);
    }
  }
}

}  // namespace
}  // namespace wavebench::model
