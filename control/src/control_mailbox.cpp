#include "avar/control/control_mailbox.hpp"

namespace avar::control {
namespace {

std::vector<std::string> without_duplicates(std::vector<std::string> names) {
  std::vector<std::string> kept;
  for (std::string& n : names) {
    bool seen = false;
    for (const std::string& k : kept) seen = seen || k == n;
    if (!seen) kept.push_back(std::move(n));
  }
  return kept;
}

}  // namespace

ControlMailbox::ControlMailbox(std::vector<std::string> names)
    : names_(without_duplicates(std::move(names))), slots_(new Slot[names_.size()]) {
  for (std::size_t i = 0; i < names_.size(); ++i) index_.emplace(names_[i], i);
}

std::size_t ControlMailbox::find(std::string_view name) const noexcept {
  const auto it = index_.find(name);
  return it == index_.end() ? names_.size() : it->second;
}

void ControlMailbox::post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept {
  const std::size_t i = find(control);
  if (i == names_.size()) {
    unknown_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  Slot& s = slots_[i];
  s.value.store(value, std::memory_order_relaxed);
  s.bipolar.store(bipolar, std::memory_order_relaxed);
  s.arrived_ns.store(arrived_ns, std::memory_order_relaxed);
  s.sequence.fetch_add(1, std::memory_order_release);
}

ControlReading ControlMailbox::read(std::size_t control) const noexcept {
  const Slot& s = slots_[control];
  ControlReading r;
  r.sequence = s.sequence.load(std::memory_order_acquire);
  r.value = s.value.load(std::memory_order_relaxed);
  r.bipolar = s.bipolar.load(std::memory_order_relaxed);
  r.arrived_ns = s.arrived_ns.load(std::memory_order_relaxed);
  return r;
}

}  // namespace avar::control
