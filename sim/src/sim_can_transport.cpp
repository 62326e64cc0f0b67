#include "avar/sim/sim_can_transport.hpp"

#include <cmath>

namespace avar::sim {

using firmware_iface::CanFrame;

SimCanTransport::SimCanTransport(SimCanBus& bus, std::string name, double max_send_wait_s)
    : bus_(bus), name_(std::move(name)), max_send_wait_s_(max_send_wait_s) {}

std::chrono::nanoseconds SimCanTransport::to_nanoseconds(double s) noexcept {
  return std::chrono::nanoseconds(std::llround(s * 1e9));
}

Status SimCanTransport::send(std::span<const CanFrame> frames) noexcept {
  for (const CanFrame& f : frames)
    if (f.error || !firmware_iface::can_frame_valid(f)) return Status::out_of_range;
  try {
    const double give_up_s = bus_.now_s() + max_send_wait_s_;
    for (const CanFrame& f : frames) {
      Status s = bus_.host_send(f);
      if (s == Status::timeout) {  // the host's queue is full: let the bus drain it first
        if (!bus_.run_until(give_up_s, SimCanBus::Until::host_sent)) return Status::timeout;
        s = bus_.host_send(f);
      }
      if (s != Status::ok) return s;
      counters_.add(&firmware_iface::FrameCounters::frames_sent);
      counters_.add(&firmware_iface::FrameCounters::bytes_sent, kBytesPerFrame);
    }
    if (!bus_.run_until(give_up_s, SimCanBus::Until::host_sent)) return bus_.host_bus_off() ? Status::io_error : Status::timeout;
    return bus_.host_bus_off() ? Status::io_error : Status::ok;
  } catch (...) {
    return Status::io_error;  // a simulated node that throws: the bus failed
  }
}

Status SimCanTransport::receive(CanFrame* frame, std::chrono::nanoseconds deadline) noexcept {
  try {
    if (!bus_.host_receive(frame)) {
      const double deadline_s = std::chrono::duration<double>(deadline).count();
      if (!bus_.run_until(std::max(deadline_s, bus_.now_s()), SimCanBus::Until::host_frame) || !bus_.host_receive(frame))
        return Status::timeout;
    }
  } catch (...) {
    return Status::io_error;
  }
  count_received(counters_, *frame);
  if (!frame->error) counters_.add(&firmware_iface::FrameCounters::bytes_received, kBytesPerFrame);
  return Status::ok;
}

Status SimCanTransport::reopen() noexcept {
  bus_.restart_host();
  bus_.host_discard();
  return Status::ok;
}

}  // namespace avar::sim
