#include "avar/sim/sim_dmx_node.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "avar/firmware_iface/artnet_dmx_codec.hpp"
#include "avar/firmware_iface/artnet_poll_codec.hpp"
#include "avar/firmware_iface/sacn_codec.hpp"

namespace avar::sim {
namespace artnet = firmware_iface::artnet;
namespace sacn = firmware_iface::sacn;

SimDmxNode::SimDmxNode(SimDmxNodeConfig config) : config_(std::move(config)), buffer_(2048) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) throw std::runtime_error("simulated DMX node: cannot open a UDP socket: " + std::string(std::strerror(errno)));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(config_.port);
  socklen_t length = sizeof a;
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &length) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error("simulated DMX node: cannot bind UDP port " + std::to_string(config_.port) +
                             " on 127.0.0.1: " + reason);
  }
  port_ = ntohs(a.sin_port);
}

SimDmxNode::~SimDmxNode() { ::close(fd_); }

std::string SimDmxNode::endpoint() const { return "127.0.0.1:" + std::to_string(port_); }

bool SimDmxNode::receive_until(std::uint64_t bytes, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    sockaddr_in from{};
    socklen_t length = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &length);
    if (n >= 0) {
      handle(std::span(buffer_.data(), static_cast<std::size_t>(n)), ntohs(from.sin_port));
      continue;
    }
    if (counters_.bytes >= bytes) return true;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd_, POLLIN, 0};
    ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 100)));
  }
}

bool SimDmxNode::in_sequence(std::uint8_t sequence) {
  if (have_sequence_) {
    const auto behind = static_cast<std::int8_t>(static_cast<std::uint8_t>(sequence - last_sequence_));
    if (behind <= 0 && behind > -20) {
      ++counters_.out_of_order;
      return false;
    }
  }
  have_sequence_ = true;
  last_sequence_ = sequence;
  return true;
}

void SimDmxNode::take(std::span<const std::uint8_t> slots) {
  ++counters_.packets;
  slot_count_ = slots.size();
  std::copy(slots.begin(), slots.end(), universe_.begin());
}

void SimDmxNode::handle(std::span<const std::uint8_t> d, std::uint16_t from_port) {
  ++counters_.datagrams;
  counters_.bytes += d.size();
  if (config_.protocol == DmxNodeProtocol::artnet) {
    if (const auto p = artnet::decode_dmx(d)) {
      if (p->port_address != config_.universe) {
        ++counters_.other_universe;
        return;
      }
      if (p->sequence != 0 && !in_sequence(p->sequence)) return;
      take(p->slots);
      return;
    }
    if (artnet::decode_poll(d)) {
      answer_poll(from_port);
      return;
    }
    ++counters_.bad_packets;
    return;
  }
  if (const auto p = sacn::decode_data(d)) {
    if (p->header.universe != config_.universe) {
      ++counters_.other_universe;
      return;
    }
    if (!in_sequence(p->header.sequence)) return;
    if ((p->header.options & sacn::kStreamTerminated) != 0) {
      ++counters_.terminated;
      return;
    }
    if (p->header.start_code != 0) return;  // alternate start codes (RDM, text) carry no levels
    priority_ = p->header.priority;
    source_name_.assign(p->source_name);
    take(p->slots);
    return;
  }
  std::array<std::uint16_t, 1> list{};
  if (sacn::decode_discovery(d, list)) {
    ++counters_.discovery;
    return;
  }
  ++counters_.bad_packets;
}

void SimDmxNode::answer_poll(std::uint16_t to_port) {
  artnet::PollReply r;
  r.ip = {127, 0, 0, 1};
  r.net_switch = static_cast<std::uint8_t>(config_.universe >> 8U);
  r.sub_switch = static_cast<std::uint8_t>((config_.universe >> 4U) & 0x0FU);
  r.short_name.set(config_.short_name);
  r.long_name.set(config_.short_name + " (simulated by avar)");
  r.node_report.set("#0001 [" + std::to_string(counters_.packets % 10000) + "] avar simulated node");
  r.num_ports = 1;
  r.port_types = {0x80, 0, 0, 0};
  r.good_output_a = {0x80, 0, 0, 0};
  r.sw_out = {static_cast<std::uint8_t>(config_.universe & 0x0FU), 0, 0, 0};
  r.bind_ip = r.ip;
  r.bind_index = 1;
  std::array<std::uint8_t, artnet::kPollReplySize> out{};
  const std::size_t n = artnet::encode_poll_reply(out, r);
  ++counters_.polls_answered;
  if (to_port == 0) return;
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  to.sin_port = htons(to_port);
  (void)::sendto(fd_, out.data(), n, MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&to), sizeof to);
}

}  // namespace avar::sim
