#include "avar/inputs/osc_input.hpp"

#include <lo/lo.h>

#include <array>
#include <cstring>
#include <stdexcept>

#include "avar/core/byte_order.hpp"
#include "avar/inputs/osc_dispatch.hpp"

namespace avar::inputs {
namespace {

constexpr int kMaxBundleDepth = 8;
constexpr std::size_t kBundleHeaderSize = 16;  // "#bundle\0" and a time tag
constexpr std::size_t kMaxArguments = 4;       // more is ignored anyway: controls take one

bool is_bundle(std::span<const std::uint8_t> data) noexcept {
  static constexpr char kTag[8] = {'#', 'b', 'u', 'n', 'd', 'l', 'e', '\0'};
  return data.size() >= sizeof kTag && std::memcmp(data.data(), kTag, sizeof kTag) == 0;
}

/// liblo's argument pointers are only 4-byte aligned (lo_arg is a union with 8-byte members):
/// read the value's bytes, never through the union.
template <class T>
T read_arg(const lo_arg* arg) noexcept {
  T value;
  std::memcpy(&value, arg, sizeof value);
  return value;
}

double number_of(char type, const lo_arg* arg) noexcept {
  switch (type) {
    case LO_FLOAT: return read_arg<float>(arg);
    case LO_DOUBLE: return read_arg<double>(arg);
    case LO_INT32: return read_arg<std::int32_t>(arg);
    case LO_INT64: return static_cast<double>(read_arg<std::int64_t>(arg));
    default: return 0.0;
  }
}

/// Whether one message set a control.
bool dispatch_message(std::span<const std::uint8_t> data, ControlSink& sink, std::int64_t arrived_ns) noexcept {
  if (data.empty()) return false;
  int result = 0;
  // lo_message_deserialise copies the data before it swaps bytes: the const_cast writes nothing.
  void* bytes = const_cast<std::uint8_t*>(data.data());
  lo_message message = lo_message_deserialise(bytes, data.size(), &result);
  if (message == nullptr) return false;
  bool set = false;
  const char* path = lo_get_path(bytes, static_cast<ssize_t>(data.size()));
  const char* types = lo_message_get_types(message);
  const auto argc = static_cast<std::size_t>(lo_message_get_argc(message));
  if (path != nullptr && types != nullptr && argc <= kMaxArguments) {
    lo_arg** argv = lo_message_get_argv(message);
    std::array<double, kMaxArguments> values{};
    for (std::size_t i = 0; i < argc; ++i) values[i] = number_of(types[i], argv[i]);
    if (const auto control = osc_control(path, std::string_view(types, argc), std::span(values.data(), argc))) {
      sink.post(control->control, control->value, false, arrived_ns);
      set = true;
    }
  }
  lo_message_free(message);
  return set;
}

void dispatch_element(std::span<const std::uint8_t> data, ControlSink& sink, std::int64_t arrived_ns, int depth,
                      InputCounters& counters) noexcept {
  const auto ignore_one = [&] { ++counters.messages, ++counters.ignored; };
  if (!is_bundle(data)) {
    ++counters.messages;
    if (!dispatch_message(data, sink, arrived_ns)) ++counters.ignored;
    return;
  }
  if (depth >= kMaxBundleDepth || data.size() < kBundleHeaderSize) return ignore_one();
  std::size_t at = kBundleHeaderSize;
  while (at < data.size()) {
    if (data.size() - at < 4) return ignore_one();
    const std::uint32_t size = get_u32_be(&data[at]);
    at += 4;
    if (size > data.size() - at) return ignore_one();
    dispatch_element(data.subspan(at, size), sink, arrived_ns, depth + 1, counters);
    at += size;
  }
}

}  // namespace

InputCounters dispatch_osc_packet(std::span<const std::uint8_t> packet, ControlSink& sink, std::int64_t arrived_ns) noexcept {
  InputCounters counters;
  dispatch_element(packet, sink, arrived_ns, 0, counters);
  return counters;
}

OscInput::OscInput(std::string host, std::uint16_t port) : listener_(std::move(host), port, "OSC") {}

OscInput::~OscInput() { stop(); }

void OscInput::start(ControlSink& sink) {
  if (sink_ != nullptr && listening_) {
    if (sink_ == &sink) return;
    throw std::logic_error(describe() + " already delivers into another sink");
  }
  // The sink is set before the thread starts, and the thread uses its own copy of the pointer.
  sink_ = &sink;
  listener_.start([this, target = &sink](std::span<const std::uint8_t> datagram, std::int64_t arrived) {
    counters_.add(dispatch_osc_packet(datagram, *target, arrived));
  });
  listening_ = true;
}

void OscInput::stop() noexcept {
  listener_.stop();
  listening_ = false;
}

std::string OscInput::describe() const { return "OSC on udp " + listener_.where(); }

std::string OscInput::bound_address() const { return listening_ ? listener_.bound_address() : ""; }

}  // namespace avar::inputs
