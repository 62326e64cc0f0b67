#pragma once
// A simulated CAN device for transport and bus tests: answers every standard data frame on
// `request_id` with a frame on request_id + 1 carrying the same bytes, after `delay_s` of its own
// time, and every remote frame on request_id with `dlc` bytes counting up from 0. Tests may also
// queue any frame (it goes out at the next arbitration) and read what it heard.

#include <deque>
#include <vector>

#include "avar/sim/can_node.hpp"

namespace avar::test {

class CanResponderNode final : public sim::CanNode {
 public:
  explicit CanResponderNode(std::uint32_t request_id, double delay_s = 0) : request_id_(request_id), delay_s_(delay_s) {}

  void receive(const firmware_iface::CanFrame& frame) override {
    heard.push_back(frame);
    if (frame.error || frame.extended || frame.id != request_id_) return;
    firmware_iface::CanFrame reply = frame;
    reply.id = request_id_ + 1;
    if (frame.rtr) {
      reply.rtr = false;
      for (std::uint8_t i = 0; i < reply.dlc; ++i) reply.data[i] = i;
    }
    reply.timestamp = {};
    waiting_.push_back({now_s_ + delay_s_, reply});
    release();
  }
  bool peek_transmit(firmware_iface::CanFrame* frame) const override {
    if (ready_.empty()) return false;
    *frame = ready_.front();
    return true;
  }
  void pop_transmit() override { ready_.pop_front(); }
  void advance(double dt_s) override {
    now_s_ += dt_s;
    release();
  }

  /// A frame to put on the bus as soon as it wins arbitration.
  void queue(const firmware_iface::CanFrame& frame) { ready_.push_back(frame); }
  std::size_t queued() const { return ready_.size(); }
  double now_s() const { return now_s_; }

  std::vector<firmware_iface::CanFrame> heard;  ///< every frame this node heard, in order

 private:
  struct Waiting {
    double due_s;
    firmware_iface::CanFrame frame;
  };
  void release() {
    while (!waiting_.empty() && waiting_.front().due_s <= now_s_ + 1e-12) {
      ready_.push_back(waiting_.front().frame);
      waiting_.pop_front();
    }
  }

  std::uint32_t request_id_;
  double delay_s_;
  double now_s_ = 0;
  std::deque<Waiting> waiting_;
  std::deque<firmware_iface::CanFrame> ready_;
};

}  // namespace avar::test
