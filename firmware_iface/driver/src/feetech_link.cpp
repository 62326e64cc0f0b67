#include "avar/firmware_iface/feetech_link.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace avar::firmware_iface {
namespace ft = feetech;
namespace {

std::uint32_t faults_from_error(std::uint8_t error) noexcept {
  std::uint32_t f = 0;
  if (error & ft::kErrorVoltage) f |= kDeviceVoltage;
  if (error & ft::kErrorAngleSensor) f |= kDeviceEncoder;
  if (error & ft::kErrorOverheat) f |= kDeviceOverheat;
  if (error & ft::kErrorOverCurrent) f |= kDeviceElectrical;
  if (error & ft::kErrorOverload) f |= kDeviceOverload;
  return f;
}

/// Checks the configuration before anything is sized; returns the IDs by actuator.
std::vector<std::uint32_t> feetech_ids(const FeetechLinkConfig& config) {
  const std::size_t n = config.actuators.size();
  if (n == 0) throw std::invalid_argument("a Feetech bus needs at least one servo");
  if (n > FeetechLink::kMaxServos)
    throw std::invalid_argument("a Feetech bus drives at most " + std::to_string(FeetechLink::kMaxServos) +
                                " servos per sync write, not " + std::to_string(n));
  std::vector<std::uint32_t> ids;
  for (const FeetechActuator& a : config.actuators) {
    if (a.id > ft::kMaxId) throw std::invalid_argument("Feetech ID " + std::to_string(a.id) + " is above 253");
    if (std::find(ids.begin(), ids.end(), a.id) != ids.end())
      throw std::invalid_argument("Feetech ID " + std::to_string(a.id) + " is used twice");
    ids.push_back(a.id);
  }
  return ids;
}

BusExchangeConfig feetech_exchange(const FeetechLinkConfig& c) {
  return {c.reply_timeout, c.retries, c.silent_exchanges, c.reconnect_every, 2 * ft::kMaxPacketSize};
}

}  // namespace

FeetechLink::FeetechLink(ByteTransport& transport, FeetechLinkConfig config)
    : transport_(transport),
      config_(std::move(config)),
      table_(config_.actuators),
      bus_(transport_, codec_, feetech_ids(config_), feetech_exchange(config_)) {
  const std::size_t n = config_.actuators.size();
  std::string ids;
  for (const FeetechActuator& a : config_.actuators) ids += (ids.empty() ? "" : ",") + std::to_string(a.id);
  ids_.resize(n);
  goals_.resize(n);
  torque_off_.assign(n, 0);
  all_slots_.resize(n);
  for (std::size_t i = 0; i < n; ++i) all_slots_[i] = i;
  packet_.resize(2 * ft::sync_write_size(2, n) + ft::sync_read_size(n));
  codec_.set_retry_read(ft::kPresentPosition, readback_length());
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

Status FeetechLink::query(std::size_t slot, std::span<const std::uint8_t> request, std::size_t data_length,
                          std::span<std::uint8_t> params) noexcept {
  std::uint8_t error = 0;
  auto take = [&](std::size_t, const BusReply& r) noexcept {
    if (r.params.size() != data_length) return false;
    error = r.error;
    std::copy_n(r.params.begin(), std::min(params.size(), r.params.size()), params.begin());
    return true;
  };
  if (const Status s = bus_.query(slot, request, ft::status_size(data_length), take); s != Status::ok) return s;
  // A processing error (checksum, range, instruction) means the servo refused the request.
  return error & (ft::kErrorChecksum | ft::kErrorInstruction) ? Status::bad_data : Status::ok;
}

Status FeetechLink::write_register(std::size_t slot, std::uint8_t address, std::span<const std::uint8_t> data) {
  std::array<std::uint8_t, ft::kMaxPacketSize> request{};
  const std::size_t len = ft::encode_write(request, config_.actuators[slot].id, address, data);
  if (!config_.replies_to_writes) return bus_.write(std::span(request.data(), len));
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
    std::array<std::uint8_t, 2> present{};
    if (const Status s = query(i, std::span(request.data(), len), 2, present); s != Status::ok) return s;
    if (const Status s = write_register(i, ft::kGoalPosition, present); s != Status::ok) return s;
    const std::uint8_t on[1] = {1};
    if (const Status s = write_register(i, ft::kTorqueEnable, on); s != Status::ok) return s;
    table_.set_release_told(i, false);
  }
  return Status::ok;
}

Status FeetechLink::read_positions(std::span<double> frame, std::span<bool> known) {
  std::array<std::uint8_t, ft::kMaxPacketSize> request{};
  for (std::size_t i = 0; i < ids_.size(); ++i) ids_[i] = config_.actuators[i].id;
  const std::size_t len = ft::encode_sync_read(request, ft::kPresentPosition, 2, ids_);
  if (const Status s = bus_.write(std::span(request.data(), len)); s != Status::ok) return s;
  auto take = [&](std::size_t slot, const BusReply& r) noexcept {
    if (r.params.size() != 2) return false;
    frame[table_.channel(slot)] =
        table_.to_channel(slot, ft::position_from_word(config_.series, ft::get_word(config_.series, r.params)));
    known[table_.channel(slot)] = true;
    return true;
  };
  return bus_.collect(all_slots_, ft::status_size(2), take);
}

Status FeetechLink::send(std::span<const double> frame) noexcept {
  bool reopened = false;  // nothing to restore: the servos kept their power and torque
  if (bus_.begin(&reopened) != Status::ok) return Status::io_error;
  const std::size_t n = config_.actuators.size();
  std::size_t driven = 0, newly_released = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (table_.released(i)) {
      if (table_.release_pending(i)) newly_released++;
      continue;
    }
    ids_[driven] = config_.actuators[i].id;
    goals_[driven++] = ft::position_word(config_.series, std::lround(table_.to_device(i, frame)));
  }
  const std::span<std::uint8_t> out(packet_);
  std::size_t size = 0;
  if (driven > 0)
    size += ft::encode_sync_write_words(out, config_.series, ft::kGoalPosition, std::span(ids_.data(), driven),
                                        std::span(goals_.data(), driven));
  if (newly_released > 0) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (table_.release_pending(i)) {
        ids_[k++] = config_.actuators[i].id;
        table_.set_release_told(i);
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
  if (const Status s = bus_.write(out.first(size)); s != Status::ok) return s;
  if (length == 0) return Status::ok;
  auto take = [&](std::size_t slot, const BusReply& r) noexcept {
    if (r.params.size() != length) return false;
    take_telemetry(slot, r, length);
    return true;
  };
  if (bus_.collect(all_slots_, ft::status_size(length), take) == Status::io_error) return Status::io_error;
  if (bus_.retry(all_slots_, ft::status_size(length), take) == Status::io_error) return Status::io_error;
  return bus_.settle(all_slots_, table_);
}

void FeetechLink::take_telemetry(std::size_t slot, const BusReply& reply, std::uint8_t length) noexcept {
  ChannelTelemetry& t = table_.telemetry(slot);
  const std::span<const std::uint8_t> p = reply.params;
  t.position = table_.to_channel(slot, ft::position_from_word(config_.series, ft::get_word(config_.series, p)));
  if (length >= 8) {
    t.load = ft::from_sign_magnitude(ft::get_word(config_.series, p.subspan(4, 2)), ft::kLoadSignBit) / 1000.0;
    t.temperature_c = p[7];
  }
  t.faults = faults_from_error(reply.error);
  ++t.updates;
}

Status FeetechLink::release() noexcept {
  std::array<std::uint8_t, ft::kMinPacketSize + 2> packet{};
  const std::uint8_t off[1] = {0};
  const std::size_t len = ft::encode_write(packet, ft::kBroadcastId, ft::kTorqueEnable, off);
  return bus_.write(std::span(packet.data(), len));
}

void FeetechLink::release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }

void FeetechLink::read_telemetry(std::span<ChannelTelemetry> out) const noexcept { table_.read_telemetry(out); }

}  // namespace avar::firmware_iface
