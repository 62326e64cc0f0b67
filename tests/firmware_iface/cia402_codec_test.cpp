// The CiA 402 profile of ../shared/protocols/canopen-cia402.md, sections 5-6: controlword
// commands, statusword decode, the transition table, and the PDO layouts avar maps.
#include "avar/firmware_iface/cia402_codec.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/canopen_codec.hpp"

namespace avar::firmware_iface::cia402 {
namespace {

TEST(Cia402Codec, ControlwordCommandsAndTheirGoldenSdoFrames) {
  EXPECT_EQ(kShutdown, 0x0006);
  EXPECT_EQ(kSwitchOn, 0x0007);
  EXPECT_EQ(kEnableOperation, 0x000F);
  EXPECT_EQ(kDisableVoltage, 0x0000);
  EXPECT_EQ(kQuickStop, 0x0002);
  EXPECT_EQ(kFaultReset, 0x0080);
  // C6 and C7.
  const CanFrame shutdown = canopen::encode_sdo_download(1, kControlword, 0, kShutdown, 2);
  const CanFrame enable = canopen::encode_sdo_download(1, kControlword, 0, kEnableOperation, 2);
  const std::uint8_t c6[8] = {0x2B, 0x40, 0x60, 0x00, 0x06, 0x00, 0x00, 0x00};
  const std::uint8_t c7[8] = {0x2B, 0x40, 0x60, 0x00, 0x0F, 0x00, 0x00, 0x00};
  EXPECT_EQ(shutdown, can_data_frame(0x601, c6));
  EXPECT_EQ(enable, can_data_frame(0x601, c7));

  EXPECT_TRUE(is_shutdown(kShutdown));
  EXPECT_TRUE(is_switch_on(kSwitchOn));
  EXPECT_TRUE(is_switch_on(kEnableOperation));  // switch on + enable operation
  EXPECT_TRUE(is_enable_operation(kEnableOperation));
  EXPECT_TRUE(is_disable_operation(kDisableOperation));
  EXPECT_TRUE(is_disable_voltage(kDisableVoltage));
  EXPECT_TRUE(is_quick_stop(kQuickStop));
  // A fault reset is none of the others.
  for (std::uint16_t cw : {std::uint16_t{0x0080}, std::uint16_t{0x0086}, std::uint16_t{0x0087}, std::uint16_t{0x008F}}) {
    EXPECT_FALSE(is_shutdown(cw) || is_switch_on(cw) || is_disable_voltage(cw) || is_quick_stop(cw) || is_enable_operation(cw) ||
                 is_disable_operation(cw))
        << std::hex << cw;
  }
}

TEST(Cia402Codec, StatuswordDecodeFollowsTheMasks) {
  EXPECT_EQ(decode_state(0x0000), State::not_ready_to_switch_on);
  EXPECT_EQ(decode_state(0x0230), State::not_ready_to_switch_on);  // bits 4, 5, 9 free under mask 0x4F
  EXPECT_EQ(decode_state(0x0040), State::switch_on_disabled);
  EXPECT_EQ(decode_state(0x0260), State::switch_on_disabled);
  EXPECT_EQ(decode_state(0x0021), State::ready_to_switch_on);
  EXPECT_EQ(decode_state(0x0231), State::ready_to_switch_on);
  EXPECT_EQ(decode_state(0x0023), State::switched_on);
  EXPECT_EQ(decode_state(0x0027), State::operation_enabled);
  EXPECT_EQ(decode_state(0x1637), State::operation_enabled);
  EXPECT_EQ(decode_state(0x0007), State::quick_stop_active);
  EXPECT_EQ(decode_state(0x0017), State::quick_stop_active);
  EXPECT_EQ(decode_state(0x000F), State::fault_reaction_active);
  EXPECT_EQ(decode_state(0x002F), State::fault_reaction_active);
  EXPECT_EQ(decode_state(0x0008), State::fault);
  EXPECT_EQ(decode_state(0x0238), State::fault);
  EXPECT_EQ(decode_state(0x0001), State::unknown);  // ready bit without quick stop bit
  EXPECT_EQ(decode_state(0x0003), State::unknown);
  for (State s : {State::not_ready_to_switch_on, State::switch_on_disabled, State::ready_to_switch_on, State::switched_on,
                  State::operation_enabled, State::quick_stop_active, State::fault_reaction_active, State::fault})
    EXPECT_EQ(decode_state(state_bits(s)), s) << state_name(s);
  EXPECT_STREQ(state_name(State::operation_enabled), "Operation enabled");
  EXPECT_STREQ(state_name(State::fault), "Fault");
}

TEST(Cia402Codec, EveryTransitionOfTheTable) {
  struct Row {
    State from;
    std::uint16_t cw;
    State to;
    int number;
  };
  const Row rows[] = {
      {State::switch_on_disabled, kShutdown, State::ready_to_switch_on, 2},
      {State::ready_to_switch_on, kSwitchOn, State::switched_on, 3},
      {State::ready_to_switch_on, kEnableOperation, State::switched_on, 3},
      {State::switched_on, kEnableOperation, State::operation_enabled, 4},
      {State::operation_enabled, kDisableOperation, State::switched_on, 5},
      {State::switched_on, kShutdown, State::ready_to_switch_on, 6},
      {State::ready_to_switch_on, kDisableVoltage, State::switch_on_disabled, 7},
      {State::ready_to_switch_on, kQuickStop, State::switch_on_disabled, 7},
      {State::operation_enabled, kShutdown, State::ready_to_switch_on, 8},
      {State::operation_enabled, kDisableVoltage, State::switch_on_disabled, 9},
      {State::switched_on, kDisableVoltage, State::switch_on_disabled, 10},
      {State::switched_on, kQuickStop, State::switch_on_disabled, 10},
      {State::operation_enabled, kQuickStop, State::quick_stop_active, 11},
      {State::quick_stop_active, kDisableVoltage, State::switch_on_disabled, 12},
      {State::fault, kFaultReset, State::switch_on_disabled, 15},
      {State::quick_stop_active, kEnableOperation, State::operation_enabled, 16},
  };
  for (const Row& r : rows) {
    const Transition t = next_state(r.from, r.cw, 0);
    EXPECT_EQ(t.to, r.to) << "transition " << r.number;
    EXPECT_EQ(t.number, r.number);
  }
  // Commands that do nothing where they arrive.
  EXPECT_EQ(next_state(State::switch_on_disabled, kEnableOperation, 0).number, 0);
  EXPECT_EQ(next_state(State::fault, kShutdown, 0).number, 0);
  EXPECT_EQ(next_state(State::fault_reaction_active, kFaultReset, 0).number, 0);
  EXPECT_EQ(next_state(State::not_ready_to_switch_on, kShutdown, 0).number, 0);
  EXPECT_EQ(next_state(State::operation_enabled, kEnableOperation, 0).number, 0);
  // Fault reset acts on the rising edge only.
  EXPECT_EQ(next_state(State::fault, kFaultReset, kFaultReset).number, 0);
  EXPECT_EQ(next_state(State::operation_enabled, kFaultReset, 0).number, 0);
}

TEST(Cia402Codec, ModeNamesAndSupportedBits) {
  EXPECT_STREQ(mode_name(8), "cyclic synchronous position");
  EXPECT_STREQ(mode_name(1), "profile position");
  EXPECT_STREQ(mode_name(-3), "vendor mode");
  EXPECT_STREQ(mode_name(42), "unknown mode");
  EXPECT_EQ(supported_mode_bit(8), 1u << 7);
  EXPECT_EQ(supported_mode_bit(1), 1u << 0);
  EXPECT_EQ(supported_mode_bit(6), 1u << 5);
  EXPECT_EQ(supported_mode_bit(10), 1u << 9);
  EXPECT_EQ(supported_mode_bit(0), 0u);
}

TEST(Cia402Codec, EmcyCodesAsDeviceFaults) {
  EXPECT_EQ(emcy_device_faults(0x0000), 0u);
  EXPECT_EQ(emcy_device_faults(0x2310), kDeviceElectrical);
  EXPECT_EQ(emcy_device_faults(0x3210), kDeviceVoltage);
  EXPECT_EQ(emcy_device_faults(0x4310), kDeviceOverheat);
  EXPECT_EQ(emcy_device_faults(0x7305), kDeviceEncoder);
  EXPECT_EQ(emcy_device_faults(0x7121), kDeviceOverload);
  EXPECT_EQ(emcy_device_faults(0x8611), kDeviceOther);
}

TEST(Cia402Codec, PdoLayoutsRoundTrip) {
  const CanFrame rpdo = encode_control_target(0x205, kEnableOperation, -10000);
  const std::uint8_t golden[6] = {0x0F, 0x00, 0xF0, 0xD8, 0xFF, 0xFF};
  EXPECT_EQ(rpdo, can_data_frame(0x205, golden));
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> word;
  for (int i = 0; i < 1000; ++i) {
    const auto node = static_cast<std::uint8_t>(1 + word(rng) % 127);
    const auto w = static_cast<std::uint16_t>(word(rng));
    const auto v = static_cast<std::int32_t>(word(rng));
    std::uint16_t w2 = 0;
    std::int32_t v2 = 0;
    ASSERT_TRUE(decode_control_target(encode_control_target(canopen::rpdo_cob_id(1, node), w, v), canopen::rpdo_cob_id(1, node),
                                      &w2, &v2));
    EXPECT_EQ(w2, w);
    EXPECT_EQ(v2, v);
    ASSERT_TRUE(decode_status_position(encode_status_position(canopen::tpdo_cob_id(1, node), w, v), canopen::tpdo_cob_id(1, node),
                                       &w2, &v2));
    EXPECT_EQ(w2, w);
    EXPECT_EQ(v2, v);
    EXPECT_FALSE(decode_status_position(encode_status_position(canopen::tpdo_cob_id(1, node), w, v),
                                        canopen::tpdo_cob_id(2, node), &w2, &v2));
  }
}

}  // namespace
}  // namespace avar::firmware_iface::cia402
