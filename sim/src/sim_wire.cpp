#include "avar/sim/sim_wire.hpp"

#include <algorithm>
#include <cstring>

namespace avar::sim {

SimWire::SimWire(ByteDevice& device, int baud, double turnaround_s, std::string name)
    : device_(device), baud_(baud), turnaround_s_(turnaround_s), name_(std::move(name)) {
  last_write_.reserve(4096);
}

void SimWire::pass(double dt_s) noexcept {
  if (dt_s <= 0) return;
  now_s_ += dt_s;
  try {
    device_.advance(dt_s);
  } catch (...) {
    // A simulated device that fails to advance behaves like one that stopped: nothing more
    // arrives, which the driver meets as timeouts.
  }
}

void SimWire::collect() noexcept {
  try {
    while (pending_size_ < pending_.size()) {
      const std::size_t n = device_.take_replies(std::span(pending_).subspan(pending_size_));
      if (n == 0) break;
      pending_size_ += n;
    }
  } catch (...) {
    // As in pass(): a failing device answers nothing.
  }
}

Status SimWire::write(std::span<const std::uint8_t> bytes) noexcept {
  if (!connected_ || !open_) {
    open_ = false;  // like a vanished USB adapter: the handle stays dead until reopened
    return Status::io_error;
  }
  pass(firmware_iface::wire_seconds(bytes.size(), baud_));
  try {
    device_.receive(bytes);
  } catch (...) {
    return Status::io_error;
  }
  bytes_written_ += bytes.size();
  ++writes_;
  if (bytes.size() <= last_write_.capacity()) last_write_.assign(bytes.begin(), bytes.end());
  return Status::ok;
}

Status SimWire::read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds timeout) noexcept {
  if (!connected_ || !open_) {
    open_ = false;
    return Status::io_error;
  }
  collect();
  if (pending_size_ == 0) {
    pass(turnaround_s_);
    collect();
  }
  if (pending_size_ < out.size()) {
    // Whatever arrives within the timeout is discarded with the failed read, as on a real port.
    pass(std::chrono::duration<double>(timeout).count());
    collect();
    if (pending_size_ < out.size()) {
      pending_size_ = 0;
      return Status::timeout;
    }
  }
  std::memcpy(out.data(), pending_.data(), out.size());
  std::memmove(pending_.data(), pending_.data() + out.size(), pending_size_ - out.size());
  pending_size_ -= out.size();
  bytes_read_ += out.size();
  pass(firmware_iface::wire_seconds(out.size(), baud_));
  return Status::ok;
}

Status SimWire::read_some(std::span<std::uint8_t> out, std::chrono::milliseconds timeout, std::size_t* got) noexcept {
  *got = 0;
  if (!connected_ || !open_) {
    open_ = false;
    return Status::io_error;
  }
  if (out.empty()) return Status::ok;
  collect();
  if (pending_size_ == 0) {
    pass(turnaround_s_);
    collect();
  }
  if (pending_size_ == 0) {
    pass(std::chrono::duration<double>(timeout).count());
    collect();
    if (pending_size_ == 0) return Status::timeout;
  }
  const std::size_t n = std::min(out.size(), pending_size_);
  std::memcpy(out.data(), pending_.data(), n);
  std::memmove(pending_.data(), pending_.data() + n, pending_size_ - n);
  pending_size_ -= n;
  bytes_read_ += n;
  pass(firmware_iface::wire_seconds(n, baud_));
  *got = n;
  return Status::ok;
}

void SimWire::discard_input() noexcept {
  collect();
  pending_size_ = 0;
}

Status SimWire::reopen() noexcept {
  if (!connected_) return Status::io_error;
  open_ = true;
  pending_size_ = 0;
  ++reopens_;
  return Status::ok;
}

}  // namespace avar::sim
