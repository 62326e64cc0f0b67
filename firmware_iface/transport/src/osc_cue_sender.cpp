#include "avar/firmware_iface/osc_cue_sender.hpp"

#include <lo/lo.h>

#include <stdexcept>

namespace avar::firmware_iface {

struct OscCueSender::Prepared {
  lo_address address = nullptr;
  lo_message message = nullptr;
  std::string path;
  ~Prepared() {
    if (message) lo_message_free(message);
    if (address) lo_address_free(address);
  }
};

OscCueSender::OscCueSender(const std::vector<OscCueMessage>& messages) {
  for (const OscCueMessage& m : messages) {
    auto p = std::make_unique<Prepared>();
    p->address = lo_address_new(m.host.c_str(), std::to_string(m.port).c_str());
    p->message = lo_message_new();
    p->path = m.address;
    for (const OscArgument& a : m.arguments) {
      if (a.type == 'f') lo_message_add_float(p->message, static_cast<float>(a.number));
      else if (a.type == 'i') lo_message_add_int32(p->message, static_cast<std::int32_t>(a.number));
      else if (a.type == 's') lo_message_add_string(p->message, a.text.c_str());
      else throw std::invalid_argument(std::string("OSC argument type '") + a.type + "' is not one of f, i, s");
    }
    prepared_.push_back(std::move(p));
  }
  // Room for every message several times over: a pass of the show fires each at most once.
  std::uint32_t size = 64;
  while (size < 4 * messages.size()) size *= 2;
  ring_.assign(size, 0);
  mask_ = size - 1;
  thread_ = std::thread([this] { run(); });
}

OscCueSender::~OscCueSender() {
  stop_.store(true, std::memory_order_release);
  wake_.fetch_add(1, std::memory_order_release);
  wake_.notify_one();
  thread_.join();
}

bool OscCueSender::fire(std::size_t index) noexcept {
  const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
  if (index >= prepared_.size() || tail - head_.load(std::memory_order_acquire) > mask_) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  ring_[tail & mask_] = static_cast<std::uint32_t>(index);
  tail_.store(tail + 1, std::memory_order_release);
  wake_.fetch_add(1, std::memory_order_release);
  wake_.notify_one();
  return true;
}

void OscCueSender::flush() {
  const std::uint32_t target = tail_.load(std::memory_order_acquire);
  for (;;) {
    const std::uint32_t head = head_.load(std::memory_order_acquire);
    if (static_cast<std::int32_t>(head - target) >= 0) return;
    head_.wait(head, std::memory_order_acquire);
  }
}

void OscCueSender::run() {
  for (;;) {
    const std::uint32_t seen = wake_.load(std::memory_order_acquire);
    std::uint32_t head = head_.load(std::memory_order_relaxed);
    while (head != tail_.load(std::memory_order_acquire)) {
      const Prepared& p = *prepared_[ring_[head & mask_]];
      if (lo_send_message(p.address, p.path.c_str(), p.message) >= 0) sent_.fetch_add(1, std::memory_order_relaxed);
      else failed_.fetch_add(1, std::memory_order_relaxed);
      head_.store(++head, std::memory_order_release);
      head_.notify_all();
    }
    if (stop_.load(std::memory_order_acquire)) return;
    wake_.wait(seen, std::memory_order_acquire);
  }
}

}  // namespace avar::firmware_iface
