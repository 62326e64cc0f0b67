#include "avar/inputs/prefixed_input_source.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace avar::inputs {

PrefixedInputSource::PrefixedInputSource(std::string prefix, std::unique_ptr<InputSource> inner)
    : prefix_(std::move(prefix)), inner_(std::move(inner)) {
  if (prefix_.empty() || prefix_.size() >= kMaxName) throw std::invalid_argument("input name: 1 to 255 characters");
}

PrefixedInputSource::~PrefixedInputSource() { stop(); }

void PrefixedInputSource::start(ControlSink& sink) {
  if (sink_ != nullptr && sink_ != &sink) throw std::logic_error(describe() + " already delivers into another sink");
  sink_ = &sink;
  try {
    inner_->start(*this);
  } catch (...) {
    sink_ = nullptr;
    throw;
  }
}

void PrefixedInputSource::stop() noexcept {
  inner_->stop();
  sink_ = nullptr;
}

std::string PrefixedInputSource::describe() const { return prefix_ + ": " + inner_->describe(); }

InputCounters PrefixedInputSource::counters() const noexcept {
  InputCounters c = inner_->counters();
  c.ignored += too_long_.load(std::memory_order_relaxed);
  return c;
}

void PrefixedInputSource::post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept {
  if (control.starts_with(kOscChannelControlPrefix)) return sink_->post(control, value, bipolar, arrived_ns);
  std::array<char, kMaxName> name;
  if (prefix_.size() + 1 + control.size() > name.size()) {
    too_long_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  char* end = std::copy(prefix_.begin(), prefix_.end(), name.data());
  *end++ = '.';
  end = std::copy(control.begin(), control.end(), end);
  sink_->post(std::string_view(name.data(), static_cast<std::size_t>(end - name.data())), value, bipolar, arrived_ns);
}

}  // namespace avar::inputs
