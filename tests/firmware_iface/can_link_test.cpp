// CanLink: the tick's order (earlier frames offered first, every set's frames in one send, replies
// collected until every set has its own), silent drives as telemetry rather than a failed link,
// bus-off as a failed link that reopens, and release.
#include "avar/firmware_iface/can_link.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <vector>

namespace avar::firmware_iface {
namespace {

/// A scripted bus: what the host sends is recorded; what it receives is queued by the test or
/// answered by `answer` (one reply per frame sent); time moves only when a receive waits.
class CanLinkScriptedBus final : public FrameTransport {
 public:
  Status send(std::span<const CanFrame> frames) noexcept override {
    if (bus_off) return Status::io_error;
    ++sends;
    for (const CanFrame& f : frames) {
      sent.push_back(f);
      ++k.frames_sent;
      if (answering && f.id >= 0x100 && f.id < 0x180) {
        CanFrame r = f;
        r.id = f.id + 0x80;
        inbox.push_back(r);
      }
    }
    return Status::ok;
  }
  Status receive(CanFrame* frame, std::chrono::nanoseconds deadline) noexcept override {
    if (inbox.empty()) {
      if (deadline > now_) now_ = deadline;
      return Status::timeout;
    }
    *frame = inbox.front();
    inbox.pop_front();
    ++k.frames_received;
    return Status::ok;
  }
  std::chrono::nanoseconds now() const noexcept override { return now_; }
  void discard_input() noexcept override { inbox.clear(); }
  Status reopen() noexcept override {
    ++reopens;
    if (stay_off) return Status::io_error;
    bus_off = false;
    return Status::ok;
  }
  int bitrate() const noexcept override { return 1'000'000; }
  FrameCounters counters() const noexcept override { return k; }
  const std::string& name() const noexcept override { return name_; }

  std::vector<CanFrame> sent;
  std::deque<CanFrame> inbox;
  bool answering = true;
  bool bus_off = false;
  bool stay_off = false;
  int sends = 0;
  int reopens = 0;

 private:
  std::chrono::nanoseconds now_{0};
  FrameCounters k;
  std::string name_ = "scripted bus";
};

struct CanLinkToyActuator {
  std::size_t channel;
  LinearCalibration calibration;
};

/// A toy drive set: actuator i commands on 0x100 + i (one byte, the device value), is answered on
/// 0x180 + i, and beats its heart on 0x700 + i; silent for `budget` ticks means lost.
class CanLinkToyDrives final : public CanDrives {
 public:
  explicit CanLinkToyDrives(const std::vector<CanLinkToyActuator>& a, std::uint32_t budget = 3)
      : CanDrives(a), answered_(a.size()), silent_(a.size()), beats_(a.size()), budget_(budget) {}
  const char* device_name() const noexcept override { return "toy drive"; }
  Status start(FrameTransport&) override { return Status::ok; }
  std::string start_problem() const override { return {}; }
  Status read_positions(FrameTransport&, std::span<double>, std::span<bool>) override { return Status::ok; }
  std::size_t max_tick_frames() const noexcept override { return table().size(); }
  void encode_tick(std::span<const double> frame, CanOutbox& out) noexcept override {
    for (std::size_t i = 0; i < table().size(); ++i) {
      answered_[i] = false;
      const std::uint8_t v = static_cast<std::uint8_t>(table().to_device(i, frame));
      const std::array<std::uint8_t, 1> data{v};
      if (!table().released(i)) static_cast<void>(out.push(can_data_frame(0x100 + static_cast<std::uint32_t>(i), data)));
    }
  }
  bool take(const CanFrame& f) noexcept override {
    if (f.id >= 0x180 && f.id < 0x180 + table().size()) {
      const std::size_t i = f.id - 0x180;
      answered_[i] = true;
      table().telemetry(i).position = table().to_channel(i, f.data[0]);
      ++table().telemetry(i).updates;
      return true;
    }
    if (f.id >= 0x700 && f.id < 0x700 + table().size()) {
      ++beats_[f.id - 0x700];
      silent_[f.id - 0x700] = 0;
      return true;
    }
    return false;
  }
  bool replies_complete() const noexcept override {
    for (std::size_t i = 0; i < table().size(); ++i)
      if (!table().released(i) && !answered_[i]) return false;
    return true;
  }
  Status settle() noexcept override {
    Status s = Status::ok;
    for (std::size_t i = 0; i < table().size(); ++i) {
      if (!answered_[i]) {
        table().forget_feedback(i);
        s = Status::timeout;
        if (++silent_[i] >= budget_) table().telemetry(i).faults |= kDeviceLost;
      } else {
        silent_[i] = 0;
      }
    }
    return s;
  }
  void encode_release(CanOutbox& out) noexcept override {
    for (std::size_t i = 0; i < table().size(); ++i)
      static_cast<void>(out.push(can_remote_frame(0x7E0 + static_cast<std::uint32_t>(i), 0)));
  }
  std::string channel_problem(std::size_t channel) const override {
    for (std::size_t i = 0; i < table().size(); ++i)
      if (table().channel(i) == channel && silent_[i] >= budget_) return "toy drive " + std::to_string(i) + ": silent";
    return {};
  }
  std::uint64_t device_errors() const noexcept override { return 0; }
  std::vector<int> beats() const { return beats_; }

 private:
  std::vector<char> answered_;
  std::vector<std::uint32_t> silent_;
  std::vector<int> beats_;
  std::uint32_t budget_;
};

struct CanLinkFixture {
  CanLinkScriptedBus* bus = nullptr;
  CanLinkToyDrives* drives = nullptr;
  std::unique_ptr<CanLink> link;

  explicit CanLinkFixture(std::size_t n) {
    std::vector<CanLinkToyActuator> actuators;
    for (std::size_t i = 0; i < n; ++i) actuators.push_back({i, {0, 100, 0, 200, false, 0}});
    auto b = std::make_unique<CanLinkScriptedBus>();
    bus = b.get();
    auto d = std::make_unique<CanLinkToyDrives>(actuators);
    drives = d.get();
    std::vector<std::unique_ptr<CanDrives>> sets;
    sets.push_back(std::move(d));
    CanLinkConfig config;
    config.reconnect_every = 3;
    link = std::make_unique<CanLink>(std::move(b), std::move(sets), config);
  }
};

TEST(CanLink, SendsEveryCommandInOneGoAndTakesTheReplies) {
  CanLinkFixture f(3);
  ASSERT_EQ(f.link->start(), Status::ok);
  const std::vector<double> frame{10, 50, 100};
  ASSERT_EQ(f.link->send(frame), Status::ok);
  EXPECT_EQ(f.bus->sends, 1);
  ASSERT_EQ(f.bus->sent.size(), 3u);
  EXPECT_EQ(f.bus->sent[1].id, 0x101u);
  EXPECT_EQ(f.bus->sent[1].data[0], 100);  // 50 of 0..100 -> 100 of 0..200
  std::vector<ChannelTelemetry> t(3);
  f.link->read_telemetry(t);
  EXPECT_DOUBLE_EQ(t[2].position, 100);
  EXPECT_EQ(t[2].updates, 1u);
  const LinkCounters k = f.link->counters();
  EXPECT_EQ(k.exchanges, 1u);
  EXPECT_EQ(k.replies, 3u);
  EXPECT_EQ(k.timeouts, 0u);
  EXPECT_EQ(f.link->stats().bits_sent, 3u * can_frame_bits(1));
  EXPECT_EQ(f.bus->now(), std::chrono::nanoseconds(0)) << "no wait once every reply is in";
}

TEST(CanLink, FramesThatCameBetweenTicksAreOfferedBeforeTheTick) {
  CanLinkFixture f(2);
  ASSERT_EQ(f.link->start(), Status::ok);
  f.bus->inbox.push_back(can_data_frame(0x701, std::array<std::uint8_t, 1>{5}));
  f.bus->inbox.push_back(can_data_frame(0x555, std::array<std::uint8_t, 1>{1}));  // nobody's
  ASSERT_EQ(f.link->send(std::vector<double>{0, 0}), Status::ok);
  EXPECT_EQ(f.drives->beats()[1], 1);
  EXPECT_EQ(f.link->stats().frames_ignored, 1u);
}

TEST(CanLink, ASilentDriveIsAChannelFaultNotAFailedLink) {
  CanLinkFixture f(2);
  ASSERT_EQ(f.link->start(), Status::ok);
  f.bus->answering = false;
  const std::vector<double> frame{0, 0};
  for (int tick = 0; tick < 3; ++tick) EXPECT_EQ(f.link->send(frame), Status::ok);
  EXPECT_EQ(f.bus->now(), std::chrono::milliseconds(15)) << "each tick waits its reply timeout (5 ms)";
  std::vector<ChannelTelemetry> t(2);
  f.link->read_telemetry(t);
  EXPECT_TRUE(t[0].faults & kDeviceLost);
  EXPECT_TRUE(std::isnan(t[0].position)) << "feedback that did not come is absent, not old";
  EXPECT_EQ(f.link->counters().timeouts, 3u);
  EXPECT_EQ(f.link->channel_problem(1), "toy drive 1: silent");
  EXPECT_EQ(f.link->channel_problem(7), "");
}

TEST(CanLink, BusOffFailsTheLinkWhichReopensNowAndThen) {
  CanLinkFixture f(1);
  ASSERT_EQ(f.link->start(), Status::ok);
  CanFrame off;
  off.error = true;
  off.id = kCanErrorBusOff;
  f.bus->inbox.push_back(off);
  EXPECT_EQ(f.link->send(std::vector<double>{1}), Status::io_error);
  f.bus->bus_off = true;
  f.bus->stay_off = true;
  EXPECT_EQ(f.link->send(std::vector<double>{1}), Status::io_error);
  EXPECT_EQ(f.link->send(std::vector<double>{1}), Status::io_error);
  EXPECT_EQ(f.bus->reopens, 0) << "reopens every third send only";
  EXPECT_EQ(f.link->send(std::vector<double>{1}), Status::io_error);
  EXPECT_EQ(f.bus->reopens, 1);
  f.bus->stay_off = false;
  for (int i = 0; i < 2; ++i) EXPECT_EQ(f.link->send(std::vector<double>{1}), Status::io_error);
  EXPECT_EQ(f.link->send(std::vector<double>{1}), Status::ok);
  EXPECT_EQ(f.link->counters().reconnects, 1u);
}

TEST(CanLink, ReleaseSendsEverySetsReleaseFramesAndReleasedChannelsGoQuiet) {
  CanLinkFixture f(2);
  ASSERT_EQ(f.link->start(), Status::ok);
  f.link->release_channel(0);
  ASSERT_EQ(f.link->send(std::vector<double>{0, 0}), Status::ok);
  ASSERT_EQ(f.bus->sent.size(), 1u);
  EXPECT_EQ(f.bus->sent[0].id, 0x101u);
  ASSERT_EQ(f.link->release(), Status::ok);
  ASSERT_EQ(f.bus->sent.size(), 3u);
  EXPECT_EQ(f.bus->sent[1].id, 0x7E0u);
  EXPECT_TRUE(f.bus->sent[2].rtr);
}

TEST(CanLink, CountsSaturatedCommands) {
  CanLinkFixture f(1);
  ASSERT_EQ(f.link->start(), Status::ok);
  ASSERT_EQ(f.link->send(std::vector<double>{250}), Status::ok);
  EXPECT_EQ(f.bus->sent[0].data[0], 200) << "saturated to the calibrated window";
  EXPECT_EQ(f.link->saturated_pulses(), 1u);
}

}  // namespace
}  // namespace avar::firmware_iface
