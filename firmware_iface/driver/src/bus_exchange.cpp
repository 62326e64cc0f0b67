#include "avar/firmware_iface/bus_exchange.hpp"

#include <algorithm>
#include <cstring>

namespace avar::firmware_iface {

BusExchange::BusExchange(ByteTransport& transport, BusCodec& codec, std::vector<std::uint32_t> devices, BusExchangeConfig config)
    : transport_(transport),
      codec_(codec),
      devices_(std::move(devices)),
      config_(config),
      reconnector_(config.reconnect_every),
      answered_(std::make_unique<bool[]>(devices_.size())),
      awaited_(std::make_unique<bool[]>(devices_.size())),
      watches_(devices_.size(), DeviceWatch(config.silent_exchanges)),
      rx_(config.max_packet),
      request_(config.max_packet) {}

Status BusExchange::begin(bool* reopened) noexcept {
  exchange_bytes_ = 0;
  std::fill_n(answered_.get(), devices_.size(), false);
  if (reconnector_.ask(transport_, reopened) != Status::ok) return Status::io_error;
  counters_.add(&LinkCounters::exchanges);
  return Status::ok;
}

Status BusExchange::write(std::span<const std::uint8_t> bytes) noexcept {
  transport_.discard_input();  // late replies of an earlier request
  const Status s = transport_.write(bytes);
  if (s == Status::io_error) reconnector_.lost();
  if (s != Status::ok) return s;
  counters_.add(&LinkCounters::bytes_sent, bytes.size());
  exchange_bytes_ += bytes.size();
  return Status::ok;
}

Status BusExchange::collect(std::span<const std::size_t> slots, std::size_t reply_size, ReplySink take) noexcept {
  using std::chrono::milliseconds;
  for (std::size_t s : slots) {
    awaited_[s] = true;
    answered_[s] = false;
  }
  const std::chrono::nanoseconds deadline = transport_.now() + config_.reply_timeout;
  const std::size_t expected = slots.size() * reply_size;
  std::size_t have = 0, taken = 0, lost = 0, bytes_read = 0;
  Status failure = Status::ok;
  while (taken + lost < slots.size()) {
    BusReply reply;
    std::size_t used = 0, want = 1;
    const Framing f = codec_.parse(std::span(rx_).first(have), &reply, &used, &want);
    if (f == Framing::need_more) {
      if (have < reply_size) want = std::max(want, reply_size - have);
      // Past the deadline, only what has already arrived is taken (reads of 0 ms), and no more
      // than the replies asked for: a late thread still collects them, a babbling line cannot
      // hold the exchange.
      const milliseconds left = std::max(milliseconds(0), std::chrono::duration_cast<milliseconds>(deadline - transport_.now()));
      if ((left.count() == 0 && bytes_read > expected) || have + want > rx_.size()) break;
      const Status s = transport_.read_exact(std::span(rx_).subspan(have, want), left);
      if (s == Status::io_error) {
        reconnector_.lost();
        failure = s;
      }
      if (s != Status::ok) break;
      counters_.add(&LinkCounters::bytes_received, want);
      exchange_bytes_ += want;
      have += want;
      bytes_read += want;
      continue;
    }
    if (f == Framing::bad_checksum) {
      counters_.add(&LinkCounters::crc_errors);
      ++lost;
    } else if (f == Framing::stray) {
      counters_.add(&LinkCounters::framing_errors, used);
    } else if (f == Framing::reply) {
      for (std::size_t s : slots) {
        if (!awaited_[s] || devices_[s] != reply.device || !take(s, reply)) continue;
        awaited_[s] = false;
        answered_[s] = true;
        ++taken;
        counters_.add(&LinkCounters::replies);
        if (reply.device_error) counters_.add(&LinkCounters::device_errors);
        break;
      }
    }
    used = std::min(used, have);
    std::memmove(rx_.data(), rx_.data() + used, have - used);
    have -= used;
  }
  for (std::size_t s : slots) awaited_[s] = false;
  if (failure != Status::ok) return failure;
  if (taken < slots.size()) {
    counters_.add(&LinkCounters::timeouts, slots.size() - taken);
    return Status::timeout;
  }
  return Status::ok;
}

Status BusExchange::query(std::size_t slot, std::span<const std::uint8_t> request, std::size_t reply_size,
                          ReplySink take) noexcept {
  if (const Status s = write(request); s != Status::ok) return s;
  const std::size_t one[1] = {slot};
  return collect(one, reply_size, take);
}

Status BusExchange::retry(std::span<const std::size_t> asked, std::size_t reply_size, ReplySink take) noexcept {
  std::uint32_t left = config_.retries;
  for (std::size_t slot : asked) {
    if (left == 0) break;
    if (answered_[slot]) continue;
    --left;
    counters_.add(&LinkCounters::retries);
    const std::size_t len = codec_.encode_retry(devices_[slot], request_);
    if (query(slot, std::span(request_).first(len), reply_size, take) == Status::io_error) return Status::io_error;
  }
  return Status::ok;
}

Status BusExchange::settle(std::span<const std::size_t> asked, ActuatorTable& table) noexcept {
  for (std::size_t slot : asked) awaited_[slot] = true;
  bool silent = false;
  for (std::size_t slot = 0; slot < devices_.size(); ++slot) {
    if (awaited_[slot] && answered_[slot]) {
      watches_[slot].answered();
      continue;
    }
    table.forget_feedback(slot);
    if (awaited_[slot]) silent = watches_[slot].missed() || silent;
    awaited_[slot] = false;
  }
  std::fill_n(awaited_.get(), devices_.size(), false);
  return silent ? Status::timeout : Status::ok;
}

LinkCounters BusExchange::counters() const noexcept {
  LinkCounters k = counters_.snapshot();
  k.reconnects = reconnector_.reconnects();
  return k;
}

}  // namespace avar::firmware_iface
