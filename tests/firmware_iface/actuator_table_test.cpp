#include "avar/firmware_iface/actuator_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace avar::firmware_iface {
namespace {

struct TableActuator {
  std::size_t channel = 0;
  LinearCalibration calibration;
};

/// Actuators 0 and 1 both follow rig channel 2 (a mirrored pair), actuator 2 follows channel 0.
std::vector<TableActuator> mirrored_pair() {
  return {{2, {0, 10, 1000, 2000, false, 0}}, {2, {0, 10, 1000, 2000, true, 0}}, {0, {-1, 1, 0, 255, false, 0}}};
}

TEST(ActuatorTable, CalibratesEachActuatorFromItsChannelAndCountsSaturation) {
  ActuatorTable table(mirrored_pair());
  const std::vector<double> frame{0.5, 99, 2.5};
  EXPECT_DOUBLE_EQ(table.to_device(0, frame), 1250);
  EXPECT_DOUBLE_EQ(table.to_device(1, frame), 1750);
  EXPECT_DOUBLE_EQ(table.to_device(2, frame), 191.25);
  EXPECT_EQ(table.saturated(), 0u);
  const std::vector<double> beyond{-3, 0, 12};
  EXPECT_DOUBLE_EQ(table.to_device(0, beyond), 2000);
  EXPECT_DOUBLE_EQ(table.to_device(2, beyond), 0);
  EXPECT_EQ(table.saturated(), 2u);
  EXPECT_DOUBLE_EQ(table.to_channel(1, 1750), 2.5);
  EXPECT_EQ(table.channel(2), 0u);
}

TEST(ActuatorTable, ReleasingAChannelReleasesEveryActuatorOnItAndTheDeviceIsToldOnce) {
  ActuatorTable table(mirrored_pair());
  table.release_channel(7);  // no actuator follows it
  for (std::size_t i = 0; i < 3; ++i) EXPECT_FALSE(table.released(i));
  table.release_channel(2);
  EXPECT_TRUE(table.released(0) && table.released(1));
  EXPECT_FALSE(table.released(2));
  EXPECT_TRUE(table.release_pending(0));
  table.set_release_told(0);
  EXPECT_FALSE(table.release_pending(0));
  EXPECT_TRUE(table.release_pending(1));
  EXPECT_FALSE(table.release_pending(2));
  table.set_release_told(0, false);  // the device forgot (torque came back on): tell it again
  EXPECT_TRUE(table.release_pending(0));
  table.release_all_told();
  for (std::size_t i = 0; i < 3; ++i) EXPECT_TRUE(table.released(i) && !table.release_pending(i));
}

TEST(ActuatorTable, TelemetryGoesToEachActuatorsChannelAndForgottenFeedbackIsUnknown) {
  ActuatorTable table(mirrored_pair());
  table.telemetry(2) = {0.25, -0.5, 41, kDeviceOverload, 9};
  std::vector<ChannelTelemetry> out(4);
  out[1].position = 7;
  table.read_telemetry(out);
  EXPECT_EQ(out[0].position, 0.25);
  EXPECT_EQ(out[0].updates, 9u);
  EXPECT_EQ(out[1].position, 7) << "channels no actuator follows are left alone";
  table.forget_feedback(2);
  table.read_telemetry(out);
  EXPECT_TRUE(std::isnan(out[0].position) && std::isnan(out[0].load) && std::isnan(out[0].temperature_c));
  EXPECT_EQ(out[0].faults, kDeviceOverload);
  EXPECT_EQ(out[0].updates, 9u);
}

}  // namespace
}  // namespace avar::firmware_iface
