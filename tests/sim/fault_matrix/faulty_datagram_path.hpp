#pragma once
// The network between a UDP sender (an Art-Net or sACN link) and a simulated node, with faults:
// the link sends to this path's socket on loopback; each advance() takes every datagram that
// arrived and hands it to the node through the plan. FaultPlan's fields read per datagram:
// drop_command loses it, duplicate_reply delivers it twice, reorder_reply delivers it after the
// next one, delay_reply_s holds it back (simulated seconds); set_connected(false) is a pulled
// cable (everything lost). One thread; for tests.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <deque>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/sim/faulty_device.hpp"
#include "avar/sim/sim_dmx_node.hpp"

namespace avar::fault_matrix {

class FaultyDatagramPath {
 public:
  FaultyDatagramPath() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd_ < 0) throw std::runtime_error("no UDP socket");
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&a), len) != 0 ||
        ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
      ::close(fd_);
      throw std::runtime_error("cannot bind a UDP socket on loopback");
    }
    port_ = ntohs(a.sin_port);
  }
  ~FaultyDatagramPath() { ::close(fd_); }
  FaultyDatagramPath(const FaultyDatagramPath&) = delete;
  FaultyDatagramPath& operator=(const FaultyDatagramPath&) = delete;

  std::string endpoint() const { return "127.0.0.1:" + std::to_string(port_); }
  void set_plan(const sim::FaultPlan& plan) {
    plan_ = plan;
    random_.seed(plan.seed);
  }
  void set_connected(bool connected) { connected_ = connected; }
  /// commands_dropped: datagrams lost (by the plan or the pulled cable); replies_duplicated,
  /// replies_reordered: datagrams delivered twice, or after their successor.
  const sim::FaultCounts& counts() const { return counts_; }
  std::uint64_t datagrams() const { return datagrams_; }

  /// Lets dt_s pass: takes in what the sender sent, delivers what is due to `node`.
  void advance(double dt_s, sim::SimDmxNode& node) {
    now_s_ += dt_s;
    std::array<std::uint8_t, 1500> buffer{};
    for (;;) {
      const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
      if (n <= 0) break;
      ++datagrams_;
      route(std::vector<std::uint8_t>(buffer.begin(), buffer.begin() + n));
    }
    while (!in_flight_.empty() && in_flight_.front().due_s <= now_s_) {
      node.handle(in_flight_.front().bytes, port_);
      in_flight_.pop_front();
    }
  }

 private:
  struct InFlight {
    double due_s;
    std::vector<std::uint8_t> bytes;
  };
  bool chance(double p) { return p > 0 && std::uniform_real_distribution<double>(0.0, 1.0)(random_) < p; }
  void route(std::vector<std::uint8_t> datagram) {
    if (!connected_ || chance(plan_.drop_command)) {
      ++counts_.commands_dropped;
      return;
    }
    if (parked_.empty() && chance(plan_.reorder_reply)) {
      parked_ = std::move(datagram);
      ++counts_.replies_reordered;
      return;
    }
    const double due = now_s_ + plan_.delay_reply_s;
    if (chance(plan_.duplicate_reply)) {
      ++counts_.replies_duplicated;
      in_flight_.push_back({due, datagram});
    }
    in_flight_.push_back({due, std::move(datagram)});
    if (!parked_.empty()) {
      in_flight_.push_back({due, std::move(parked_)});
      parked_.clear();
    }
  }

  int fd_ = -1;
  std::uint16_t port_ = 0;
  sim::FaultPlan plan_;
  bool connected_ = true;
  std::mt19937_64 random_{1};
  sim::FaultCounts counts_;
  double now_s_ = 0;
  std::uint64_t datagrams_ = 0;
  std::deque<InFlight> in_flight_;
  std::vector<std::uint8_t> parked_;
};

}  // namespace avar::fault_matrix
