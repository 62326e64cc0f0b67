#include "avar/firmware_iface/feetech_link.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::firmware_iface {
namespace ft = feetech;
namespace {

using Clock = std::chrono::steady_clock;

std::uint32_t faults_from_error(std::uint8_t error) noexcept {
  std::uint32_t f = 0;
  if (error & ft::kErrorVoltage) f |= kDeviceVoltage;
  if (error & ft::kErrorAngleSensor) f |= kDeviceEncoder;
  if (error & ft::kErrorOverheat) f |= kDeviceOverheat;
  if (error & ft::kErrorOverCurrent) f |= kDeviceElectrical;
  if (error & ft::kErrorOverload) f |= kDeviceOverload;
  return f;
}

}  // namespace

FeetechLink::FeetechLink(ByteTransport& transport, FeetechLinkConfig config)
    : transport_(transport), config_(std::move(config)), reconnector_(config_.reconnect_every) {
  const std::size_t n = config_.actuators.size();
  if (n == 0) throw std::invalid_argument("a Feetech bus needs at least one servo");
  if (n > kMaxServos)
    throw std::invalid_argument("a Feetech bus drives at most " + std::to_string(kMaxServos) + " servos per sync write, not " +
                                std::to_string(n));
  std::string ids;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t id = config_.actuators[i].id;
    if (id > ft::kMaxId) throw std::invalid_argument("Feetech ID " + std::to_string(id) + " is above 253");
    for (std::size_t j = 0; j < i; ++j)
      if (config_.actuators[j].id == id) throw std::invalid_argument("Feetech ID " + std::to_string(id) + " is used twice");
    ids += (ids.empty() ? "" : ",") + std::to_string(id);
  }
  released_ = std::make_unique<std::atomic<bool>[]>(n);
  torque_off_sent_.assign(n, false);
  ids_.resize(n);
  goals_.resize(n);
  torque_off_.assign(n, 0);
  all_slots_.resize(n);
  for (std::size_t i = 0; i < n; ++i) all_slots_[i] = i;
  answered_.assign(n, false);
  missed_.assign(n, 0);
  telemetry_.resize(n);
  packet_.resize(2 * ft::sync_write_size(2, n) + ft::sync_read_size(n));
  description_ = std::string("Feetech ") + (config_.series == ft::Series::sts ? "STS" : "SCS") + " bus (IDs " + ids + ", " +
                 std::to_string(config_.baud) + " baud) on " + transport_.name();
}

std::uint8_t FeetechLink::readback_length() const noexcept {
  switch (config_.readback) {
    case FeetechReadback::none: return 0;
    case FeetechReadback::position: return 2;
    case FeetechReadback::full: return 8;
  }
  return 0;
}

std::size_t FeetechLink::reply_bytes_per_tick() const noexcept {
  return config_.readback == FeetechReadback::none ? 0 : config_.actuators.size() * ft::status_size(readback_length());
}

template <class Take>
Status FeetechLink::collect(std::span<const std::size_t> slots, std::size_t data_length, Take&& take) noexcept {
  for (std::size_t s : slots) answered_[s] = false;
  const Clock::time_point deadline = Clock::now() + config_.reply_timeout;
  const std::size_t reply_size = ft::status_size(data_length);
  const std::size_t expected = slots.size() * reply_size;
  std::size_t have = 0, taken = 0, bytes_read = 0;
  bool corrupt = false;
  while (taken < slots.size()) {
    ft::Packet packet;
    std::size_t used = 0;
    const ft::DecodeResult r = ft::decode_packet(std::span(rx_.data(), have), &packet, &used);
    if (r == ft::DecodeResult::need_more) {
      // Ask for the rest of the packet under way, or for one whole reply.
      const std::size_t want = have >= ft::kHeaderSize ? ft::kHeaderSize + rx_[3] - have : reply_size - have;
      // Past the deadline, only what has already arrived is taken (reads of 0 ms), and no more
      // than the replies asked for: a late thread still collects them, a babbling line cannot
      // hold the tick.
      const auto left = std::max(std::chrono::milliseconds(0),
                                 std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
      if ((left.count() == 0 && bytes_read > expected) || have + want > rx_.size()) break;
      if (transport_.read_exact(std::span(rx_.data() + have, want), left) != Status::ok) break;
      AtomicLinkCounters::add(counters_.bytes_received, want);
      have += want;
      bytes_read += want;
      continue;
    }
    if (r == ft::DecodeResult::bad_checksum) {
      AtomicLinkCounters::add(counters_.crc_errors);
      corrupt = true;
    } else if (r == ft::DecodeResult::bad_framing) {
      AtomicLinkCounters::add(counters_.framing_errors, used);
      corrupt = true;
    } else {
      // A reply of the right size from a servo still awaited; anything else is a stray.
      for (std::size_t s : slots) {
        if (answered_[s] || config_.actuators[s].id != packet.id || packet.params.size() != data_length) continue;
        answered_[s] = true;
        ++taken;
        AtomicLinkCounters::add(counters_.replies);
        if (packet.code != 0) AtomicLinkCounters::add(counters_.device_errors);
        take(s, packet);
        break;
      }
    }
    std::copy(rx_.begin() + static_cast<long>(used), rx_.begin() + static_cast<long>(have), rx_.begin());
    have -= used;
  }
  if (taken < slots.size()) {
    AtomicLinkCounters::add(counters_.timeouts, slots.size() - taken);
    return Status::timeout;
  }
  return corrupt ? Status::bad_data : Status::ok;
}

Status FeetechLink::query(std::size_t slot, std::span<const std::uint8_t> request, std::size_t data_length,
                          ft::Packet* reply) noexcept {
  transport_.discard_input();
  if (const Status s = transport_.write(request); s != Status::ok) return s;
  AtomicLinkCounters::add(counters_.exchanges);
  AtomicLinkCounters::add(counters_.bytes_sent, request.size());
  const std::size_t one[1] = {slot};
  std::uint8_t error = 0;
  const Status s = collect(one, data_length, [&](std::size_t, const ft::Packet& p) {
    error = p.code;
    if (reply) *reply = p;
  });
  if (s != Status::ok) return s;
  // A processing error (checksum, range, instruction) means the servo refused the request.
  return error & (ft::kErrorChecksum | ft::kErrorInstruction) ? Status::bad_data : Status::ok;
}

Status FeetechLink::write_register(std::size_t slot, std::uint8_t address, std::span<const std::uint8_t> data) {
  std::array<std::uint8_t, ft::kMaxPacketSize> request{};
  const std::size_t len = ft::encode_write(request, config_.actuators[slot].id, address, data);
  if (!config_.replies_to_writes) {
    transport_.discard_input();
    AtomicLinkCounters::add(counters_.exchanges);
    AtomicLinkCounters::add(counters_.bytes_sent, len);
    return transport_.write(std::span(request.data(), len));
  }
  return query(slot, std::span(request.data(), len), 0);
}

Status FeetechLink::start() {
  std::array<std::uint8_t, ft::kMaxPacketSize> request{};
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) {
    const std::size_t len = ft::encode_ping(request, config_.actuators[i].id);
    if (const Status s = query(i, std::span(request.data(), len), 0); s != Status::ok) return s;
  }
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) {
    const FeetechActuator& a = config_.actuators[i];
    // Absent limits are 0, which the servo reads as "its maximum".
    std::array<std::uint8_t, 2> word{};
    const double speed = a.speed_steps_per_s ? std::clamp(*a.speed_steps_per_s, 1.0, 32767.0) : 0;
    ft::put_word(config_.series, word, static_cast<std::uint16_t>(std::lround(speed)));
    if (const Status s = write_register(i, ft::kGoalSpeed, word); s != Status::ok) return s;
    const double acc = a.acceleration_steps_per_s2 ? std::clamp(*a.acceleration_steps_per_s2 / 100.0, 1.0, 254.0) : 0;
    const std::uint8_t acc_byte[1] = {static_cast<std::uint8_t>(std::lround(acc))};
    if (const Status s = write_register(i, ft::kAcceleration, acc_byte); s != Status::ok) return s;
    // Hold where the servo is when torque comes on.
    const std::size_t len = ft::encode_read(request, a.id, ft::kPresentPosition, 2);
    ft::Packet reply;
    if (const Status s = query(i, std::span(request.data(), len), 2, &reply); s != Status::ok) return s;
    if (const Status s = write_register(i, ft::kGoalPosition, reply.params); s != Status::ok) return s;
    const std::uint8_t on[1] = {1};
    if (const Status s = write_register(i, ft::kTorqueEnable, on); s != Status::ok) return s;
    torque_off_sent_[i] = false;
  }
  return Status::ok;
}

Status FeetechLink::read_positions(std::span<double> frame, std::span<bool> known) {
  std::array<std::uint8_t, ft::kMaxPacketSize> request{};
  for (std::size_t i = 0; i < ids_.size(); ++i) ids_[i] = config_.actuators[i].id;
  const std::size_t len = ft::encode_sync_read(request, ft::kPresentPosition, 2, ids_);
  transport_.discard_input();
  if (const Status s = transport_.write(std::span(request.data(), len)); s != Status::ok) return s;
  AtomicLinkCounters::add(counters_.exchanges);
  AtomicLinkCounters::add(counters_.bytes_sent, len);
  return collect(all_slots_, 2, [&](std::size_t slot, const ft::Packet& p) {
    const FeetechActuator& a = config_.actuators[slot];
    frame[a.channel] = a.calibration.to_channel(ft::position_from_word(config_.series, ft::get_word(config_.series, p.params)));
    known[a.channel] = true;
  });
}

Status FeetechLink::send(std::span<const double> frame) noexcept {
  bool reopened = false;  // nothing to restore: the servos kept their power and torque
  if (reconnector_.ask(transport_, &reopened) != Status::ok) return Status::io_error;
  const std::size_t n = config_.actuators.size();
  std::size_t driven = 0, newly_released = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const FeetechActuator& a = config_.actuators[i];
    if (released_[i].load(std::memory_order_relaxed)) {
      if (!torque_off_sent_[i]) newly_released++;
      continue;
    }
    bool clamped = false;
    const double steps = a.calibration.to_device(frame[a.channel], &clamped);
    if (clamped) saturated_.fetch_add(1, std::memory_order_relaxed);
    ids_[driven] = a.id;
    goals_[driven++] = ft::position_word(config_.series, std::lround(steps));
  }
  const std::span<std::uint8_t> out(packet_);
  std::size_t size = 0;
  if (driven > 0)
    size += ft::encode_sync_write_words(out, config_.series, ft::kGoalPosition, std::span(ids_.data(), driven),
                                        std::span(goals_.data(), driven));
  if (newly_released > 0) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (released_[i].load(std::memory_order_relaxed) && !torque_off_sent_[i]) {
        ids_[k++] = config_.actuators[i].id;
        torque_off_sent_[i] = true;
      }
    size += ft::encode_sync_write(out.subspan(size), ft::kTorqueEnable, 1, std::span(ids_.data(), k),
                                  std::span(torque_off_.data(), k));
  }
  const std::uint8_t length = readback_length();
  if (length > 0) {
    for (std::size_t i = 0; i < n; ++i) ids_[i] = config_.actuators[i].id;
    size += ft::encode_sync_read(out.subspan(size), ft::kPresentPosition, length, ids_);
  }
  last_send_size_ = size;
  if (size == 0) return Status::ok;
  transport_.discard_input();  // late replies of an earlier tick
  if (const Status s = transport_.write(out.first(size)); s != Status::ok) {
    if (s == Status::io_error) reconnector_.lost();
    return s;
  }
  AtomicLinkCounters::add(counters_.exchanges);
  AtomicLinkCounters::add(counters_.bytes_sent, size);
  if (length == 0) return Status::ok;
  const auto take = [&](std::size_t slot, const ft::Packet& p) { take_telemetry(slot, p, length); };
  if (collect(all_slots_, length, take) == Status::io_error) {
    reconnector_.lost();
    return Status::io_error;
  }
  // Bounded retries, each a plain Read of a servo whose reply was lost or corrupt; a servo silent
  // for silent_exchanges sends in a row is a timeout (the controller's watchdog fault).
  std::uint32_t retries = config_.retries;
  bool silent = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!answered_[i] && retries > 0 && !released_[i].load(std::memory_order_relaxed)) {
      --retries;
      AtomicLinkCounters::add(counters_.retries);
      std::array<std::uint8_t, ft::kMaxPacketSize> request{};
      const std::size_t len = ft::encode_read(request, config_.actuators[i].id, ft::kPresentPosition, length);
      ft::Packet reply;
      const Status r = query(i, std::span(request.data(), len), length, &reply);
      if (r == Status::io_error) {
        reconnector_.lost();
        return r;
      }
      if (r == Status::ok) take_telemetry(i, reply, length);
    }
    if (answered_[i]) {
      missed_[i] = 0;
    } else {
      // Stale feedback is absent, not old.
      telemetry_[i].position = ChannelTelemetry::kUnknown;
      telemetry_[i].load = ChannelTelemetry::kUnknown;
      telemetry_[i].temperature_c = ChannelTelemetry::kUnknown;
      silent = silent || ++missed_[i] >= config_.silent_exchanges;
    }
  }
  return silent ? Status::timeout : Status::ok;
}

void FeetechLink::take_telemetry(std::size_t slot, const ft::Packet& p, std::uint8_t length) noexcept {
  ChannelTelemetry& t = telemetry_[slot];
  t.position = config_.actuators[slot].calibration.to_channel(ft::position_from_word(config_.series, ft::get_word(config_.series, p.params)));
  if (length >= 8) {
    t.load = ft::from_sign_magnitude(ft::get_word(config_.series, p.params.subspan(4, 2)), ft::kLoadSignBit) / 1000.0;
    t.temperature_c = p.params[7];
  }
  t.faults = faults_from_error(p.code);
  ++t.updates;
}

Status FeetechLink::release() noexcept {
  std::array<std::uint8_t, ft::kMinPacketSize + 2> packet{};
  const std::uint8_t off[1] = {0};
  const std::size_t len = ft::encode_write(packet, ft::kBroadcastId, ft::kTorqueEnable, off);
  AtomicLinkCounters::add(counters_.exchanges);
  AtomicLinkCounters::add(counters_.bytes_sent, len);
  return transport_.write(std::span(packet.data(), len));
}

void FeetechLink::release_channel(std::size_t channel) noexcept {
  for (std::size_t i = 0; i < config_.actuators.size(); ++i)
    if (config_.actuators[i].channel == channel) released_[i].store(true, std::memory_order_relaxed);
}

void FeetechLink::read_telemetry(std::span<ChannelTelemetry> out) const noexcept {
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) out[config_.actuators[i].channel] = telemetry_[i];
}

}  // namespace avar::firmware_iface
