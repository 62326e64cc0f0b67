// send() of the Feetech, SSC-32 and DMX links allocates nothing, read-back included (the one
// allocation-counting file of this test binary: it replaces the global operator new).
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "../support/allocation_counter.hpp"
#include "avar/firmware_iface/dmx_link.hpp"
#include "avar/firmware_iface/feetech_link.hpp"
#include "avar/firmware_iface/ssc32_link.hpp"

namespace avar::firmware_iface {
namespace {

/// Answers every read from a fixed script, round and round; sizes everything up front.
class ScriptedTransport final : public ByteTransport {
 public:
  explicit ScriptedTransport(std::vector<std::uint8_t> script) : script_(std::move(script)) {}
  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    written_ += bytes.size();
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds) noexcept override {
    for (std::uint8_t& b : out) {
      b = script_[at_];
      at_ = (at_ + 1) % script_.size();
    }
    return Status::ok;
  }
  std::chrono::nanoseconds now() const noexcept override { return {}; }
  void discard_input() noexcept override {}
  Status reopen() noexcept override { return Status::ok; }
  std::uint64_t bytes_written() const noexcept override { return written_; }
  const std::string& name() const noexcept override { return name_; }

 private:
  std::vector<std::uint8_t> script_;
  std::size_t at_ = 0;
  std::uint64_t written_ = 0;
  std::string name_ = "scripted";
};

std::vector<std::uint8_t> feetech_replies(std::span<const std::uint8_t> ids) {
  std::vector<std::uint8_t> out;
  for (std::uint8_t id : ids) {
    const std::uint8_t data[8] = {0x00, 0x08, 0, 0, 0x10, 0x04, 120, 31};  // 2048, load -16, 12 V, 31 °C
    std::array<std::uint8_t, feetech::kMaxPacketSize> packet{};
    const std::size_t n = feetech::encode_packet(packet, id, 0, data);
    out.insert(out.end(), packet.begin(), packet.begin() + static_cast<long>(n));
  }
  return out;
}

TEST(LinkAllocation, FeetechSendWithFullReadBackAllocatesNothing) {
  const std::uint8_t ids[4] = {1, 2, 3, 4};
  ScriptedTransport t(feetech_replies(ids));
  FeetechLinkConfig config;
  for (std::size_t i = 0; i < 4; ++i) config.actuators.push_back({i, ids[i], {-90, 90, 1024, 3072, false, 0}, {}, {}});
  FeetechLink link(t, config);
  std::array<double, 4> frame{1, 2, 3, 4};
  std::array<ChannelTelemetry, 4> telemetry{};
  link.release_channel(2);
  const long before = testing::allocations.load();
  for (int tick = 0; tick < 100; ++tick) {
    frame[0] = tick * 0.5;
    ASSERT_EQ(link.send(frame), Status::ok);
    link.read_telemetry(telemetry);
    (void)link.counters();
  }
  EXPECT_EQ(testing::allocations.load() - before, 0);
  EXPECT_NEAR(telemetry[3].position, 0, 1e-9);
  EXPECT_NEAR(telemetry[3].load, -0.016, 1e-9);
  EXPECT_EQ(telemetry[3].temperature_c, 31);
  EXPECT_EQ(link.counters().replies, 400u);
}

TEST(LinkAllocation, Ssc32AndDmxSendsAllocateNothing) {
  ScriptedTransport t({0});
  Ssc32LinkConfig ssc;
  DmxLinkConfig dmx;
  for (std::size_t i = 0; i < 8; ++i) {
    ssc.actuators.push_back({i, static_cast<int>(i), {-90, 90, 1000, 2000, false, 0}, 3000.0});
    dmx.actuators.push_back({i, static_cast<int>(1 + 2 * i), i % 2 == 0, {-90, 90, 0, i % 2 == 0 ? 65535.0 : 255.0, false, 0}});
  }
  Ssc32Link ssc_link(t, ssc);
  DmxLink dmx_link(t, dmx);
  std::array<double, 8> frame{};
  ssc_link.release_channel(3);
  dmx_link.release_channel(3);
  const long before = testing::allocations.load();
  for (int tick = 0; tick < 100; ++tick) {
    frame[1] = tick * 0.5;
    ASSERT_EQ(ssc_link.send(frame), Status::ok);
    ASSERT_EQ(dmx_link.send(frame), Status::ok);
  }
  ASSERT_EQ(ssc_link.release(), Status::ok);
  ASSERT_EQ(dmx_link.release(), Status::ok);
  EXPECT_EQ(testing::allocations.load() - before, 0);
}

}  // namespace
}  // namespace avar::firmware_iface
