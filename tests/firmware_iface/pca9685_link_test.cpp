// Hobby servos on a PCA9685 over I2C, at the I2C seam: the link's start-up leaves the simulated
// board at 50 Hz with every output off, sends write only what changed and put each channel's
// pulse on its output to the count, a released channel goes limp, release() switches everything
// off at once, a board that stops answering is counted, and bad configurations are refused. A
// real bus (/dev/i2c-N) is opened where the machine has one.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "avar/firmware_iface/linux_i2c_bus.hpp"
#include "avar/firmware_iface/pca9685_codec.hpp"
#include "avar/firmware_iface/pca9685_link.hpp"
#include "avar/sim/sim_i2c_bus.hpp"

namespace avar::firmware_iface {
namespace {

namespace pca = pca9685;

// Two servos: channel 0 (-90..90 deg -> 1000..2000 us) on output 3, channel 1 (0..100 % ->
// 500..2500 us) on output 12.
Pca9685LinkConfig two_servos() {
  Pca9685LinkConfig c;
  c.outputs = {{0, 3, LinearCalibration{-90, 90, 1000, 2000, false, 0}}, {1, 12, LinearCalibration{0, 100, 500, 2500, false, 0}}};
  c.description = "PCA9685 link 'head' at 0x40";
  return c;
}

TEST(Pca9685Link, StartsTheBoardAt50HzWithEveryOutputOff) {
  auto bus = std::make_shared<sim::SimI2cBus>();
  bus->add_pca9685(0x40);
  Pca9685Link link(bus, two_servos());
  ASSERT_EQ(link.start(), Status::ok);
  const pca::Registers r = bus->registers(0x40);
  EXPECT_EQ(r.value[pca::kPreScale], 121);
  EXPECT_EQ(r.value[pca::kMode1], 0xa1);
  EXPECT_EQ(r.value[pca::kMode2], 0x04);
  for (std::uint8_t o = 0; o < 16; ++o) EXPECT_EQ(pca::pulse_counts(r, o), 0) << "output " << o;
  const auto writes = bus->writes(0x40);
  ASSERT_EQ(writes.size(), 6u);
  EXPECT_EQ(writes[0], (std::vector<std::uint8_t>{0x00, 0x31}));
  EXPECT_EQ(writes[5], (std::vector<std::uint8_t>{0xfa, 0x00, 0x00, 0x00, 0x10}));
  EXPECT_EQ(bus->settled_us(), 500u) << "the oscillator's start-up, waited on the bus";
}

TEST(Pca9685Link, PutsEachChannelsPulseOnItsOutputAndWritesOnlyChanges) {
  auto bus = std::make_shared<sim::SimI2cBus>();
  bus->add_pca9685(0x40);
  Pca9685Link link(bus, two_servos());
  ASSERT_EQ(link.start(), Status::ok);
  std::vector<double> frame = {0, 25};  // 1500 us and 1000 us
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), 3), 307);  // 1500 us / 4.88 us
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), 12), 205);
  EXPECT_NEAR(bus->pulse_us(0x40, 3), 1500, 4.88 / 2);
  EXPECT_EQ(link.output_writes(), 2u);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(link.output_writes(), 2u) << "nothing changed, nothing written";
  frame[0] = 90;
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), 3), 410);  // 2000 us
  EXPECT_EQ(link.output_writes(), 3u);
  frame[1] = 500;  // beyond the calibration: saturated to 2500 us, and counted
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), 12), 512);
  EXPECT_GE(link.saturated_pulses(), 1u);
}

TEST(Pca9685Link, ReleasedChannelsGoLimpAndReleaseSwitchesAllOff) {
  auto bus = std::make_shared<sim::SimI2cBus>();
  bus->add_pca9685(0x40);
  Pca9685Link link(bus, two_servos());
  ASSERT_EQ(link.start(), Status::ok);
  const std::vector<double> frame = {0, 50};
  ASSERT_EQ(link.send(frame), Status::ok);
  link.release_channel(1);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), 12), 0);
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), 3), 307);
  ASSERT_EQ(link.release(), Status::ok);
  for (std::uint8_t o = 0; o < 16; ++o) EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), o), 0);
  ASSERT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x40), 3), 0) << "released stays off";
}

TEST(Pca9685Link, ABoardThatStopsAnsweringIsCountedAndSaid) {
  auto bus = std::make_shared<sim::SimI2cBus>();
  bus->add_pca9685(0x41);
  Pca9685LinkConfig wrong = two_servos();
  Pca9685Link absent(bus, wrong);  // no board at 0x40
  EXPECT_EQ(absent.start(), Status::io_error);
  EXPECT_NE(absent.start_problem().find("does not answer"), std::string::npos) << absent.start_problem();
  wrong.address = 0x41;
  Pca9685Link link(bus, wrong);
  ASSERT_EQ(link.start(), Status::ok);
  bus->set_answering(0x41, false);
  EXPECT_EQ(link.send(std::vector<double>{0, 50}), Status::io_error);
  EXPECT_EQ(link.counters().device_errors, 2u);
  bus->set_answering(0x41, true);
  EXPECT_EQ(link.send(std::vector<double>{0, 50}), Status::ok) << "the writes that failed are tried again";
  EXPECT_EQ(pca::pulse_counts(bus->registers(0x41), 3), 307);
}

TEST(Pca9685Link, RefusesConfigurationsTheBoardCannotHave) {
  auto bus = std::make_shared<sim::SimI2cBus>();
  Pca9685LinkConfig c = two_servos();
  c.outputs[1].output = 16;
  EXPECT_THROW(Pca9685Link(bus, c), std::invalid_argument);
  c = two_servos();
  c.outputs[1].output = 3;
  EXPECT_THROW(Pca9685Link(bus, c), std::invalid_argument);
  c = two_servos();
  c.address = 0x78;
  EXPECT_THROW(Pca9685Link(bus, c), std::invalid_argument);
  c = two_servos();
  c.frequency_hz = 2000;
  EXPECT_THROW(Pca9685Link(bus, c), std::invalid_argument);
  c.frequency_hz = 10;
  EXPECT_THROW(Pca9685Link(bus, c), std::invalid_argument);
  c.outputs.clear();
  c.frequency_hz = 50;
  EXPECT_THROW(Pca9685Link(bus, c), std::invalid_argument);
}

TEST(Pca9685Link, OpensARealBusWhereThereIsOne) {
  std::string path;
  for (int n = 0; n < 16 && path.empty(); ++n)
    if (std::filesystem::exists("/dev/i2c-" + std::to_string(n))) path = "/dev/i2c-" + std::to_string(n);
  if (path.empty()) {
    EXPECT_THROW(open_i2c_bus("/dev/i2c-0"), std::runtime_error);
    GTEST_SKIP() << "no /dev/i2c-N on this machine (load i2c-dev, or enable I2C on a Raspberry Pi)";
  }
  const std::unique_ptr<I2cBus> bus = open_i2c_bus(path);
  EXPECT_EQ(bus->describe(), "I2C bus " + path);
}

}  // namespace
}  // namespace avar::firmware_iface
