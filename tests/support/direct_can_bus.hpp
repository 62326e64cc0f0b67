#pragma once
// A FrameTransport wired straight to simulated CAN nodes, for drive tests that need no bus
// timing: every frame the host sends reaches every node at once, nodes' frames come back in
// arbitration order, and time (simulated) passes only while the host waits for a frame, in 1 ms
// steps, advancing every node. Deterministic; single-threaded.

#include <algorithm>
#include <chrono>
#include <deque>
#include <string>
#include <vector>

#include "avar/firmware_iface/frame_transport.hpp"
#include "avar/sim/can_node.hpp"

namespace avar::test {

class DirectCanBus final : public firmware_iface::FrameTransport {
 public:
  explicit DirectCanBus(std::vector<sim::CanNode*> nodes, int bitrate = 1'000'000)
      : nodes_(std::move(nodes)), bitrate_(bitrate) {}

  Status send(std::span<const firmware_iface::CanFrame> frames) noexcept override {
    for (const auto& f : frames) {
      sent.push_back(f);
      ++counters_.frames_sent;
      for (sim::CanNode* n : nodes_)
        if (n && attached(n)) n->receive(f);
      drain();
    }
    return Status::ok;
  }
  Status receive(firmware_iface::CanFrame* frame, std::chrono::nanoseconds deadline) noexcept override {
    for (;;) {
      drain();
      if (!inbox_.empty()) {
        *frame = inbox_.front();
        inbox_.pop_front();
        frame->timestamp = now_;
        ++counters_.frames_received;
        return Status::ok;
      }
      if (now_ >= deadline) return Status::timeout;
      advance(std::chrono::milliseconds(1));
    }
  }
  std::chrono::nanoseconds now() const noexcept override { return now_; }
  void discard_input() noexcept override { inbox_.clear(); }
  Status reopen() noexcept override { return Status::ok; }
  int bitrate() const noexcept override { return bitrate_; }
  firmware_iface::FrameCounters counters() const noexcept override { return counters_; }
  const std::string& name() const noexcept override { return name_; }

  /// Lets simulated time pass for every node (and collects what they send meanwhile).
  void advance(std::chrono::nanoseconds dt) {
    for (sim::CanNode* n : nodes_)
      if (n) n->advance(std::chrono::duration<double>(dt).count());
    now_ += dt;
    drain();
  }
  /// A node that drops off the bus (false) hears and says nothing until it comes back.
  void set_attached(sim::CanNode* node, bool on) {
    std::erase(detached_, node);
    if (!on) detached_.push_back(node);
  }

  std::vector<firmware_iface::CanFrame> sent;  ///< every frame the host sent, in order

 private:
  bool attached(sim::CanNode* n) const { return std::find(detached_.begin(), detached_.end(), n) == detached_.end(); }
  /// Moves the nodes' pending frames to the host, lowest id first, each also heard by the others.
  void drain() {
    for (;;) {
      sim::CanNode* winner = nullptr;
      firmware_iface::CanFrame best, f;
      for (sim::CanNode* n : nodes_)
        if (n && attached(n) && n->peek_transmit(&f) && (!winner || f.id < best.id)) {
          winner = n;
          best = f;
        }
      if (!winner) return;
      winner->pop_transmit();
      if (!attached(winner)) continue;
      for (sim::CanNode* n : nodes_)
        if (n && n != winner && attached(n)) n->receive(best);
      inbox_.push_back(best);
    }
  }

  std::vector<sim::CanNode*> nodes_;
  std::vector<sim::CanNode*> detached_;
  int bitrate_;
  std::deque<firmware_iface::CanFrame> inbox_;
  std::chrono::nanoseconds now_{0};
  firmware_iface::FrameCounters counters_;
  std::string name_ = "direct CAN bus";
};

}  // namespace avar::test
