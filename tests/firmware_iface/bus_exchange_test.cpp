// BusExchange on a toy protocol (so that nothing here depends on a servo's codec): replies
// A5 DEV LEN PAYLOAD... SUM, a retry is 'R' DEV. The transport answers each request from a
// script and keeps a clock of its own that only waits advance, so every deadline is exact.
#include "avar/firmware_iface/bus_exchange.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <functional>
#include <vector>

namespace avar::firmware_iface {
namespace {

using namespace std::chrono_literals;
using ToyBytes = std::vector<std::uint8_t>;

ToyBytes toy_reply(std::uint8_t device, ToyBytes payload, bool corrupt = false) {
  ToyBytes r;
  r.reserve(4 + payload.size());
  r.push_back(0xA5);
  r.push_back(device);
  r.push_back(static_cast<std::uint8_t>(payload.size()));
  for (std::uint8_t p : payload) r.push_back(p);
  std::uint8_t sum = 0;
  for (std::size_t i = 1; i < r.size(); ++i) sum = static_cast<std::uint8_t>(sum + r[i]);
  r.push_back(static_cast<std::uint8_t>(corrupt ? sum + 1 : sum));
  return r;
}

class ToyCodec final : public BusCodec {
 public:
  Framing parse(std::span<const std::uint8_t> in, BusReply* reply, std::size_t* used, std::size_t* want) noexcept override {
    *used = 0;
    if (!in.empty() && in[0] != 0xA5) {
      *used = 1;
      return Framing::stray;
    }
    const std::size_t total = in.size() >= 3 ? 4 + in[2] : 4;
    if (in.size() < total) {
      *want = total - in.size();
      return Framing::need_more;
    }
    *used = total;
    std::uint8_t sum = 0;
    for (std::size_t i = 1; i + 1 < total; ++i) sum = static_cast<std::uint8_t>(sum + in[i]);
    if (sum != in[total - 1]) return Framing::bad_checksum;
    reply->device = in[1];
    reply->error = 0;
    reply->device_error = in[2] == 0;  // an empty reply stands for a refusal in this toy
    reply->params = in.subspan(3, in[2]);
    return Framing::reply;
  }
  std::size_t encode_retry(std::uint32_t device, std::span<std::uint8_t> out) noexcept override {
    out[0] = 'R';
    out[1] = static_cast<std::uint8_t>(device);
    return 2;
  }
};

/// Each write is answered by `answer` (the request in, the bytes that arrive out); every byte
/// read costs 10 µs, a read that cannot be filled costs its whole timeout.
class ToyWire final : public ByteTransport {
 public:
  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    if (unplugged) return Status::io_error;
    requests.emplace_back(bytes.begin(), bytes.end());
    const ToyBytes r = answer ? answer(requests.back()) : ToyBytes{};
    pending.insert(pending.end(), r.begin(), r.end());
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds timeout) noexcept override {
    if (unplugged) return Status::io_error;
    reads_ms.push_back(timeout.count());
    clock += late_by;  // the reading thread was held up
    late_by = {};
    if (pending.size() < out.size()) {
      clock += timeout;
      pending.clear();
      return Status::timeout;
    }
    for (std::uint8_t& b : out) {
      b = pending.front();
      pending.pop_front();
    }
    clock += out.size() * 10us;
    return Status::ok;
  }
  std::chrono::nanoseconds now() const noexcept override { return clock; }
  void discard_input() noexcept override { pending.clear(); }
  Status reopen() noexcept override {
    ++reopens;
    return unplugged ? Status::io_error : Status::ok;
  }
  std::uint64_t bytes_written() const noexcept override { return 0; }
  const std::string& name() const noexcept override { return name_; }

  std::function<ToyBytes(const ToyBytes&)> answer;
  std::deque<std::uint8_t> pending;
  std::vector<ToyBytes> requests;
  std::vector<long> reads_ms;
  std::chrono::nanoseconds clock{0};
  std::chrono::nanoseconds late_by{0};  ///< added to the clock by the next read
  bool unplugged = false;
  int reopens = 0;

 private:
  std::string name_ = "toy";
};

/// Three devices, 7, 8 and 9, in slots 0, 1 and 2, each on its own rig channel.
struct ToyBus {
  explicit ToyBus(BusExchangeConfig config = {}) : bus(wire, codec, {7, 8, 9}, config) {}
  ToyWire wire;
  ToyCodec codec;
  BusExchange bus;
  std::vector<std::size_t> all{0, 1, 2};
  std::vector<std::uint32_t> taken;  ///< devices, in the order taken
  bool take_reply(std::size_t slot, const BusReply& r) {
    taken.push_back(r.device);
    return r.params.size() == 1 && slot == r.device - 7;
  }
  Status collect() {
    auto take = [this](std::size_t slot, const BusReply& r) noexcept { return take_reply(slot, r); };
    return bus.collect(all, 5, take);
  }
  Status retry() {
    auto take = [this](std::size_t slot, const BusReply& r) noexcept { return take_reply(slot, r); };
    return bus.retry(all, 5, take);
  }
};

struct ToyActuator {
  std::size_t channel = 0;
  LinearCalibration calibration;
};

/// Replies of the given devices, in that order, to a request of any kind; retries ('R' DEV)
/// are answered by the device asked when it is in `retry_answers`.
std::function<ToyBytes(const ToyBytes&)> toy_devices(std::vector<std::uint8_t> answer,
                                                     std::vector<std::uint8_t> retry_answers = {}) {
  return [=](const ToyBytes& request) {
    ToyBytes out;
    if (request[0] == 'R') {
      for (std::uint8_t d : retry_answers)
        if (d == request[1]) out = toy_reply(d, {d});
      return out;
    }
    for (std::uint8_t d : answer) {
      const ToyBytes r = toy_reply(d, {d});
      out.insert(out.end(), r.begin(), r.end());
    }
    return out;
  };
}

TEST(BusExchange, CollectTakesEveryReplyInAnyOrderAndCountsIt) {
  ToyBus t;
  t.wire.answer = toy_devices({9, 7, 8});
  bool reopened = true;
  ASSERT_EQ(t.bus.begin(&reopened), Status::ok);
  EXPECT_FALSE(reopened);
  const std::uint8_t request[] = {'S'};
  ASSERT_EQ(t.bus.write(request), Status::ok);
  EXPECT_EQ(t.collect(), Status::ok);
  EXPECT_EQ(t.taken, (std::vector<std::uint32_t>{9, 7, 8}));
  for (std::size_t s = 0; s < 3; ++s) EXPECT_TRUE(t.bus.answered(s));
  const LinkCounters k = t.bus.counters();
  EXPECT_EQ(k.exchanges, 1u);
  EXPECT_EQ(k.replies, 3u);
  EXPECT_EQ(k.bytes_sent, 1u);
  EXPECT_EQ(k.bytes_received, 15u);
  EXPECT_EQ(k.timeouts + k.crc_errors + k.framing_errors + k.retries, 0u);
  EXPECT_EQ(t.bus.exchange_bytes(), 16u);
}

TEST(BusExchange, AMissingReplyCostsTheDeadlineOnceAndIsRetried) {
  BusExchangeConfig config;
  config.reply_timeout = 4ms;
  ToyBus t(config);
  t.wire.answer = toy_devices({7, 9}, {8});
  bool reopened = false;
  ASSERT_EQ(t.bus.begin(&reopened), Status::ok);
  const std::uint8_t request[] = {'S'};
  ASSERT_EQ(t.bus.write(request), Status::ok);
  EXPECT_EQ(t.collect(), Status::timeout);
  EXPECT_FALSE(t.bus.answered(1));
  EXPECT_EQ(t.bus.counters().timeouts, 1u);
  // The wait for the silent device ends by the deadline on the transport's clock.
  EXPECT_GT(t.wire.clock, 3ms);
  EXPECT_LE(t.wire.clock, 100us + 4ms);
  EXPECT_EQ(t.retry(), Status::ok);
  EXPECT_TRUE(t.bus.answered(1));
  EXPECT_EQ(t.wire.requests.back(), (ToyBytes{'R', 8}));
  EXPECT_EQ(t.bus.counters().retries, 1u);
  EXPECT_EQ(t.bus.counters().replies, 3u);
}

TEST(BusExchange, RetriesAreBoundedPerExchange) {
  BusExchangeConfig config;
  config.retries = 2;
  ToyBus t(config);
  t.wire.answer = toy_devices({});
  bool reopened = false;
  for (int exchange = 1; exchange <= 2; ++exchange) {
    ASSERT_EQ(t.bus.begin(&reopened), Status::ok);
    const std::uint8_t request[] = {'S'};
    ASSERT_EQ(t.bus.write(request), Status::ok);
    EXPECT_EQ(t.collect(), Status::timeout);
    EXPECT_EQ(t.retry(), Status::ok);
    EXPECT_EQ(t.bus.counters().retries, 2u * static_cast<unsigned>(exchange));
  }
  EXPECT_EQ(t.wire.requests.size(), 6u);  // per exchange: the request and two retries
  EXPECT_EQ(t.bus.counters().timeouts, 2u * (3 + 2));
}

TEST(BusExchange, StaleFeedbackIsAbsentNotOld) {
  ToyBus t;
  t.wire.answer = toy_devices({7, 9});
  const std::vector<ToyActuator> actuators(3);
  ActuatorTable table(actuators);
  for (std::size_t i = 0; i < 3; ++i) table.telemetry(i) = {10.0 + static_cast<double>(i), 0.5, 40, kDeviceOverheat, 3};
  bool reopened = false;
  ASSERT_EQ(t.bus.begin(&reopened), Status::ok);
  const std::uint8_t request[] = {'S'};
  ASSERT_EQ(t.bus.write(request), Status::ok);
  (void)t.collect();
  // Slot 2 answered but was not asked for this time: its feedback is not of this exchange either.
  const std::size_t asked[] = {0, 1};
  EXPECT_EQ(t.bus.settle(asked, table), Status::ok);
  EXPECT_EQ(table.telemetry(0).position, 10.0);
  for (std::size_t i : {1u, 2u}) {
    const ChannelTelemetry& s = table.telemetry(i);
    EXPECT_TRUE(std::isnan(s.position) && std::isnan(s.load) && std::isnan(s.temperature_c)) << i;
    EXPECT_EQ(s.faults, kDeviceOverheat) << "fault bits stay as of the last reply";
    EXPECT_EQ(s.updates, 3u);
  }
}

TEST(BusExchange, ADeviceSilentForSilentExchangesInARowIsATimeout) {
  BusExchangeConfig config;
  config.silent_exchanges = 3;
  ToyBus t(config);
  const std::vector<ToyActuator> actuators(3);
  ActuatorTable table(actuators);
  const auto exchange = [&](std::vector<std::uint8_t> answering) {
    t.wire.answer = toy_devices(answering);
    bool reopened = false;
    EXPECT_EQ(t.bus.begin(&reopened), Status::ok);
    const std::uint8_t request[] = {'S'};
    EXPECT_EQ(t.bus.write(request), Status::ok);
    (void)t.collect();
    return t.bus.settle(t.all, table);
  };
  EXPECT_EQ(exchange({7, 9}), Status::ok);
  EXPECT_EQ(exchange({7, 9}), Status::ok);
  EXPECT_EQ(exchange({7, 8, 9}), Status::ok);  // an answer starts the count again
  EXPECT_EQ(exchange({7, 9}), Status::ok);
  EXPECT_EQ(exchange({7, 9}), Status::ok);
  EXPECT_EQ(exchange({7, 9}), Status::timeout);
}

TEST(BusExchange, CorruptAndStrayBytesAreCountedAndSyncIsKept) {
  BusExchangeConfig config;
  config.reply_timeout = 4ms;
  ToyBus t(config);
  t.wire.answer = [](const ToyBytes&) {
    ToyBytes out{0x00, 0x13};  // noise before the first reply
    for (const ToyBytes& r : {toy_reply(7, {7}), toy_reply(8, {8}, true), toy_reply(9, {9, 9}), toy_reply(9, {9})})
      out.insert(out.end(), r.begin(), r.end());
    return out;
  };
  bool reopened = false;
  ASSERT_EQ(t.bus.begin(&reopened), Status::ok);
  const std::uint8_t request[] = {'S'};
  ASSERT_EQ(t.bus.write(request), Status::ok);
  EXPECT_EQ(t.collect(), Status::timeout);  // device 8's reply was corrupt
  const LinkCounters k = t.bus.counters();
  EXPECT_EQ(k.framing_errors, 2u);
  EXPECT_EQ(k.crc_errors, 1u);
  EXPECT_EQ(k.replies, 2u);  // the two-byte reply of 9 is a stray, its next one is taken
  EXPECT_EQ(k.timeouts, 1u);
  EXPECT_EQ(k.device_errors, 0u);
  EXPECT_TRUE(t.bus.answered(0));
  EXPECT_FALSE(t.bus.answered(1));
  EXPECT_TRUE(t.bus.answered(2));
  // A corrupt reply is a reply lost, not one still to come: no deadline was waited out.
  EXPECT_LT(t.wire.clock, 1ms);
}

TEST(BusExchange, PastTheDeadlineOnlyWhatHasArrivedIsTaken) {
  BusExchangeConfig config;
  config.reply_timeout = 4ms;
  ToyBus t(config);
  // A late thread: the clock passes the deadline while the first reply is read.
  t.wire.answer = toy_devices({7, 8, 9});
  bool reopened = false;
  ASSERT_EQ(t.bus.begin(&reopened), Status::ok);
  const std::uint8_t request[] = {'S'};
  ASSERT_EQ(t.bus.write(request), Status::ok);
  t.wire.late_by = 10ms;
  EXPECT_EQ(t.collect(), Status::ok);
  EXPECT_EQ(t.bus.counters().replies, 3u);
  ASSERT_EQ(t.wire.reads_ms.size(), 3u);
  EXPECT_EQ(t.wire.reads_ms[0], 4);
  EXPECT_EQ(t.wire.reads_ms[1], 0);
  EXPECT_EQ(t.wire.reads_ms[2], 0);
  // A babbling line past the deadline: no more bytes than the replies asked for are read.
  t.wire.answer = [](const ToyBytes&) {
    ToyBytes out;
    for (int i = 0; i < 40; ++i) {
      const ToyBytes r = toy_reply(5, {5});
      out.insert(out.end(), r.begin(), r.end());
    }
    return out;
  };
  ASSERT_EQ(t.bus.write(request), Status::ok);
  t.wire.late_by = 10ms;
  const std::uint64_t before = t.bus.counters().bytes_received;
  EXPECT_EQ(t.collect(), Status::timeout);
  EXPECT_LE(t.bus.counters().bytes_received - before, 3u * 5 + 5);
  EXPECT_EQ(t.bus.counters().timeouts, 3u);
}

TEST(BusExchange, AnIoErrorMarksThePortLostAndBeginReopensItNowAndThen) {
  BusExchangeConfig config;
  config.reconnect_every = 3;
  ToyBus t(config);
  t.wire.answer = toy_devices({7, 8, 9});
  bool reopened = false;
  ASSERT_EQ(t.bus.begin(&reopened), Status::ok);
  t.wire.unplugged = true;
  const std::uint8_t request[] = {'S'};
  EXPECT_EQ(t.bus.write(request), Status::io_error);
  EXPECT_EQ(t.bus.begin(&reopened), Status::io_error);
  EXPECT_EQ(t.bus.begin(&reopened), Status::io_error);
  EXPECT_EQ(t.wire.reopens, 0);
  EXPECT_EQ(t.bus.begin(&reopened), Status::io_error);  // the third asks the transport, still gone
  EXPECT_EQ(t.wire.reopens, 1);
  t.wire.unplugged = false;
  EXPECT_EQ(t.bus.begin(&reopened), Status::io_error);
  EXPECT_EQ(t.bus.begin(&reopened), Status::io_error);
  EXPECT_EQ(t.bus.begin(&reopened), Status::ok);
  EXPECT_TRUE(reopened);
  EXPECT_EQ(t.bus.counters().reconnects, 1u);
  EXPECT_EQ(t.bus.counters().exchanges, 2u);  // the exchanges that reached the transport
  ASSERT_EQ(t.bus.write(request), Status::ok);
  t.wire.unplugged = true;
  EXPECT_EQ(t.collect(), Status::io_error);
  EXPECT_EQ(t.bus.begin(&reopened), Status::io_error);
}

TEST(BusExchange, QueryAsksOneDeviceAndSkipsTheOthers) {
  ToyBus t;
  t.wire.answer = toy_devices({7, 8, 9});
  const std::uint8_t request[] = {'Q', 9};
  auto take = [&](std::size_t slot, const BusReply& r) noexcept { return t.take_reply(slot, r); };
  EXPECT_EQ(t.bus.query(2, request, 5, take), Status::ok);
  EXPECT_EQ(t.taken, (std::vector<std::uint32_t>{9}));
  EXPECT_EQ(t.bus.counters().replies, 1u);
  EXPECT_TRUE(t.bus.answered(2));
  EXPECT_FALSE(t.bus.answered(0));
}

}  // namespace
}  // namespace avar::firmware_iface
