#include "avar/sim/sim_can_bus.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace avar::sim {
namespace {

using firmware_iface::CanFrame;

/// The arbitration field as one number, lower wins: the 11 base identifier bits, then the bit
/// after them (RTR of a standard frame, the recessive SRR of an extended one), IDE, and for
/// extended frames the 18 identifier extension bits and RTR.
std::uint64_t arbitration_key(const CanFrame& f) noexcept {
  if (!f.extended) return (std::uint64_t{f.id} << 21) | (std::uint64_t{f.rtr} << 20);
  const std::uint64_t base = f.id >> 18, extension = f.id & 0x3FFFF;
  return (base << 21) | (1ull << 20) | (1ull << 19) | (extension << 1) | std::uint64_t{f.rtr};
}

/// Frames a bus in instant timing delivers at one instant before it stops (nodes answering each
/// other forever would otherwise hang the caller).
constexpr std::size_t kMaxInstantFrames = 1'000'000;

}  // namespace

SimCanBus::SimCanBus(SimCanBusConfig config, const std::vector<CanNode*>& nodes)
    : config_(config),
      tx_(std::max<std::size_t>(1, config.host_tx_capacity)),
      rx_(std::max<std::size_t>(1, config.host_rx_capacity)) {
  if (config_.bitrate <= 0) config_.bitrate = 1'000'000;
  if (!(config_.idle_step_s > 0)) config_.idle_step_s = 1e-4;
  for (CanNode* n : nodes)
    if (n) add_node(*n);
}

void SimCanBus::add_node(CanNode& node) { nodes_.push_back({&node, true}); }

void SimCanBus::set_attached(const CanNode& node, bool attached) noexcept {
  for (Node& n : nodes_)
    if (n.node == &node) n.attached = attached;
}

bool SimCanBus::attached(const CanNode& node) const noexcept {
  for (const Node& n : nodes_)
    if (n.node == &node) return n.attached;
  return false;
}

Status SimCanBus::host_send(const CanFrame& frame) noexcept {
  if (frame.error || !firmware_iface::can_frame_valid(frame)) return Status::out_of_range;
  if (!host_online_ || host_bus_off_) return Status::io_error;
  if (tx_count_ == tx_.size()) return Status::timeout;
  tx_[(tx_first_ + tx_count_) % tx_.size()] = frame;
  ++tx_count_;
  return Status::ok;
}

bool SimCanBus::host_receive(CanFrame* frame) noexcept {
  if (rx_count_ == 0) return false;
  *frame = rx_[rx_first_];
  rx_first_ = (rx_first_ + 1) % rx_.size();
  --rx_count_;
  return true;
}

void SimCanBus::set_host_online(bool online) noexcept {
  host_online_ = online;
  if (!online) {
    tx_first_ = tx_count_ = 0;
    host_discard();
  }
}

void SimCanBus::to_host(const CanFrame& frame) noexcept {
  if (rx_count_ == rx_.size()) {
    ++stats_.host_overruns;
    return;
  }
  CanFrame& slot = rx_[(rx_first_ + rx_count_) % rx_.size()];
  slot = frame;
  slot.timestamp = std::chrono::nanoseconds(std::llround(now_s_ * 1e9));
  ++rx_count_;
}

void SimCanBus::inject_error(std::uint32_t classes) noexcept {
  if (classes & firmware_iface::kCanErrorBusOff) {
    inject_bus_off();
    classes &= ~static_cast<std::uint32_t>(firmware_iface::kCanErrorBusOff);
    if (classes == 0) return;
  }
  CanFrame f;
  f.error = true;
  f.id = classes;
  to_host(f);
}

void SimCanBus::inject_bus_off() noexcept {
  host_bus_off_ = true;
  tx_first_ = tx_count_ = 0;
  CanFrame f;
  f.error = true;
  f.id = firmware_iface::kCanErrorBusOff;
  to_host(f);
}

void SimCanBus::advance_nodes(double dt_s) {
  if (dt_s <= 0) return;
  for (Node& n : nodes_) n.node->advance(dt_s);
}

void SimCanBus::drop_detached_frames() {
  CanFrame f;
  for (Node& n : nodes_)
    if (!n.attached)
      while (n.node->peek_transmit(&f)) n.node->pop_transmit();
}

std::size_t SimCanBus::arbitrate(CanFrame* frame) {
  std::size_t winner = kNone;
  std::uint64_t best = 0;
  if (tx_count_ > 0 && host_online_ && !host_bus_off_) {
    winner = kHost;
    *frame = tx_[tx_first_];
    best = arbitration_key(*frame);
  }
  CanFrame f;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (!nodes_[i].attached) continue;
    CanNode& node = *nodes_[i].node;
    while (node.peek_transmit(&f) && (f.error || !firmware_iface::can_frame_valid(f)))
      node.pop_transmit();  // a node cannot put error frames or invalid frames on a bus
    if (!node.peek_transmit(&f)) continue;
    const std::uint64_t key = arbitration_key(f);
    if (winner == kNone || key < best) {
      winner = i;
      best = key;
      *frame = f;
    }
  }
  return winner;
}

void SimCanBus::start(std::size_t sender, const CanFrame& frame) {
  if (sender == kHost) {
    tx_first_ = (tx_first_ + 1) % tx_.size();
    --tx_count_;
    ++stats_.host_frames;
  } else {
    nodes_[sender].node->pop_transmit();
  }
  const int bits = firmware_iface::can_frame_bits(frame);
  ++stats_.frames;
  stats_.bits += static_cast<std::uint64_t>(bits);
  stats_.busy_s += frame_seconds(frame);
  if (config_.timing == SimCanTiming::instant) {
    deliver(sender, frame);
    return;
  }
  in_flight_ = true;
  in_flight_from_host_ = sender == kHost;
  in_flight_sender_ = sender;
  in_flight_frame_ = frame;
  in_flight_end_s_ = now_s_ + frame_seconds(frame);
}

void SimCanBus::deliver(std::size_t sender, const CanFrame& frame) {
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (i != sender && nodes_[i].attached) nodes_[i].node->receive(frame);
  if (sender != kHost && host_online_ && !host_bus_off_) to_host(frame);
}

bool SimCanBus::done(Until until) const noexcept {
  switch (until) {
    case Until::time: return false;
    case Until::host_frame: return rx_count_ > 0;
    case Until::host_sent: return host_unsent() == 0;
  }
  return false;
}

bool SimCanBus::run_until(double end_s, Until until) {
  std::size_t instant_frames = 0;
  for (;;) {
    drop_detached_frames();
    if (in_flight_) {
      if (in_flight_end_s_ > end_s) {  // still on the wire at the end: finishes next run
        advance_nodes(end_s - now_s_);
        now_s_ = std::max(now_s_, end_s);
        return until == Until::time || done(until);
      }
      advance_nodes(in_flight_end_s_ - now_s_);
      now_s_ = in_flight_end_s_;
      in_flight_ = false;
      in_flight_from_host_ = false;
      deliver(in_flight_sender_, in_flight_frame_);
      continue;
    }
    if (done(until)) return true;
    CanFrame frame;
    if (const std::size_t sender = arbitrate(&frame); sender != kNone && instant_frames < kMaxInstantFrames) {
      start(sender, frame);
      if (config_.timing == SimCanTiming::instant) ++instant_frames;
      continue;
    }
    const double left = end_s - now_s_;
    if (left <= 0) return until == Until::time;
    instant_frames = 0;
    if (left <= config_.idle_step_s) {
      advance_nodes(left);
      now_s_ = end_s;
    } else {
      advance_nodes(config_.idle_step_s);
      now_s_ += config_.idle_step_s;
    }
  }
}

SimCanBusStatistics SimCanBus::statistics() const noexcept {
  SimCanBusStatistics s = stats_;
  s.elapsed_s = now_s_ - stats_start_s_;
  return s;
}

void SimCanBus::reset_statistics() noexcept {
  stats_ = {};
  stats_start_s_ = now_s_;
}

}  // namespace avar::sim
