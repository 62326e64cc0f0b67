#include "avar/sim/faulty_device.hpp"

#include <array>

namespace avar::sim {

FaultyDevice::FaultyDevice(ByteDevice& inner, FaultPlan plan) : inner_(inner), plan_(plan), random_(plan.seed) {}

void FaultyDevice::set_plan(const FaultPlan& plan) {
  plan_ = plan;
  random_.seed(plan.seed);
}

bool FaultyDevice::chance(double p) {
  if (p <= 0) return false;
  return std::uniform_real_distribution<double>(0.0, 1.0)(random_) < p;
}

void FaultyDevice::receive(std::span<const std::uint8_t> bytes) {
  bytes_received_ += bytes.size();
  if (chance(plan_.drop_command)) {
    ++counts_.commands_dropped;
    return;
  }
  inner_.receive(bytes);
}

std::uint8_t FaultyDevice::random_byte() {
  return static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(random_));
}

void FaultyDevice::collect() {
  std::array<std::uint8_t, 1024> buffer{};
  std::vector<std::uint8_t> chunk;
  for (std::size_t n = inner_.take_replies(buffer); n > 0; n = inner_.take_replies(buffer))
    chunk.insert(chunk.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n));
  if (chunk.empty()) return;
  if (plan_.garbage) {
    for (std::uint8_t& b : chunk) b = random_byte();
    ++counts_.replies_garbled;
    counts_.garbage_bytes += chunk.size();
    hold(std::move(chunk));
    return;
  }
  if (plan_.silent) {
    ++counts_.replies_silenced;
    return;
  }
  if (chance(plan_.drop_reply)) {
    ++counts_.replies_dropped;
    return;
  }
  if (chance(plan_.corrupt_reply)) {
    const auto at = std::uniform_int_distribution<std::size_t>(0, chunk.size() - 1)(random_);
    const auto bit = std::uniform_int_distribution<int>(0, 7)(random_);
    chunk[at] = static_cast<std::uint8_t>(chunk[at] ^ (1u << bit));
    ++counts_.replies_corrupted;
  }
  if (chunk.size() > 1 && chance(plan_.truncate_reply)) {
    chunk.resize(std::uniform_int_distribution<std::size_t>(1, chunk.size() - 1)(random_));
    ++counts_.replies_truncated;
  }
  if (parked_.empty() && chance(plan_.reorder_reply)) {
    parked_ = std::move(chunk);
    ++counts_.replies_reordered;
    return;
  }
  hold(std::move(chunk));
  if (!parked_.empty()) {
    held_.push_back({now_s_ + plan_.delay_reply_s, std::move(parked_)});
    parked_.clear();
  }
}

void FaultyDevice::hold(std::vector<std::uint8_t> chunk) {
  const bool twice = chance(plan_.duplicate_reply);
  if (twice) ++counts_.replies_duplicated;
  const double release = now_s_ + plan_.delay_reply_s;
  if (twice) held_.push_back({release, chunk});
  held_.push_back({release, std::move(chunk)});
}

std::size_t FaultyDevice::take_replies(std::span<std::uint8_t> out) {
  collect();
  while (!held_.empty() && held_.front().release_s <= now_s_) {
    ready_.insert(ready_.end(), held_.front().bytes.begin(), held_.front().bytes.end());
    held_.pop_front();
  }
  std::size_t n = 0;
  while (n < out.size() && !ready_.empty()) {
    out[n++] = ready_.front();
    ready_.pop_front();
  }
  return n;
}

void FaultyDevice::advance(double dt_s) {
  collect();  // replies queued before this moment start their delay now
  now_s_ += dt_s;
  inner_.advance(dt_s);
  if (!plan_.garbage) return;
  garbage_owed_ += dt_s * kGarbageBytesPerSecond;
  for (; garbage_owed_ >= 1; garbage_owed_ -= 1) {
    ready_.push_back(random_byte());
    ++counts_.garbage_bytes;
  }
}

}  // namespace avar::sim
