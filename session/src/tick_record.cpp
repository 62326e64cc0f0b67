#include "avar/session/tick_record.hpp"

namespace avar::session {

TickRing::TickRing(std::size_t capacity, std::size_t channels, std::size_t links, std::size_t controls)
    : slots_(capacity < 2 ? 2 : capacity),
      channel_rows_(slots_.size() * channels),
      link_rows_(slots_.size() * links),
      control_rows_(slots_.size() * controls) {
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    slots_[i].channels = std::span<ChannelRecord>(channel_rows_.data() + i * channels, channels);
    slots_[i].links = std::span<firmware_iface::LinkCounters>(link_rows_.data() + i * links, links);
    slots_[i].controls = std::span<double>(control_rows_.data() + i * controls, controls);
  }
}

TickRecord* TickRing::claim() noexcept {
  const std::uint64_t p = published_.load(std::memory_order_relaxed);
  if (p - consumed_.load(std::memory_order_acquire) >= slots_.size()) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return nullptr;
  }
  return &slots_[p % slots_.size()];
}

void TickRing::publish() noexcept {
  published_.fetch_add(1, std::memory_order_release);
  signal_.fetch_add(1, std::memory_order_release);
  signal_.notify_one();
}

const TickRecord* TickRing::front() const noexcept {
  const std::uint64_t c = consumed_.load(std::memory_order_relaxed);
  if (c == published_.load(std::memory_order_acquire)) return nullptr;
  return &slots_[c % slots_.size()];
}

void TickRing::pop() noexcept { consumed_.fetch_add(1, std::memory_order_release); }

}  // namespace avar::session
