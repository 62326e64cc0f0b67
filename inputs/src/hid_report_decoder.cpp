#include "avar/inputs/hid_report_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>

namespace avar::inputs::hid {

namespace {

// Generic Desktop usages with names of their own.
constexpr std::uint16_t kX = 0x30;
constexpr std::uint16_t kRz = 0x35;

bool is_bipolar_axis(Usage u) { return usage_page(u) == kGenericDesktopPage && usage_id(u) >= kX && usage_id(u) <= kRz; }

bool is_hat(Usage u) { return usage_page(u) == kGenericDesktopPage && usage_id(u) == kHatSwitch; }

// floor((a + b + 1) / 2) for any signs.
std::int64_t rest_of(std::int64_t minimum, std::int64_t maximum) {
  const std::int64_t sum = minimum + maximum + 1;
  return sum >= 0 ? sum / 2 : -((-sum + 1) / 2);
}

// The field's raw value: bit_size (<= 32) bits from bit `offset` of `data`, LSB first, sign
// extended when the field is signed. false when the bits are not all in `data`.
bool extract(std::span<const std::uint8_t> data, std::uint64_t offset, std::uint32_t bit_size, bool is_signed,
             std::int64_t* value) noexcept {
  if (bit_size == 0 || bit_size > 32 || offset + bit_size > std::uint64_t{data.size()} * 8) return false;
  const std::size_t first = offset / 8;
  const std::size_t last = (offset + bit_size - 1) / 8;
  std::uint64_t bits = 0;
  for (std::size_t i = last + 1; i-- > first;) bits = (bits << 8) | data[i];
  bits >>= offset % 8;
  bits &= (std::uint64_t{1} << bit_size) - 1;
  if (is_signed && (bits >> (bit_size - 1)) != 0) {
    *value = static_cast<std::int64_t>(bits) - (std::int64_t{1} << bit_size);
  } else {
    *value = static_cast<std::int64_t>(bits);
  }
  return true;
}

}  // namespace

std::string usage_control_name(Usage usage) {
  static const char* const desktop[] = {"x", "y", "z", "rx", "ry", "rz", "slider", "dial", "wheel", "hat"};
  if (usage_page(usage) == kGenericDesktopPage && usage_id(usage) >= kX && usage_id(usage) <= kHatSwitch)
    return desktop[usage_id(usage) - kX];
  if (usage_page(usage) == kButtonPage) return "button" + std::to_string(usage_id(usage));
  char buf[24];
  std::snprintf(buf, sizeof buf, "usage_%04X_%04X", usage_page(usage), usage_id(usage));
  return buf;
}

ReportDecoder::ReportDecoder(const ReportDescriptor& descriptor)
    : fields_(descriptor.fields), numbered_(descriptor.numbered), max_report_bytes_(descriptor.max_report_bytes()) {
  // Entries grouped by report id (stable: descriptor order within a report); controls are named
  // in descriptor order.
  std::vector<Entry> in_order;
  std::map<std::string, int> seen;
  std::uint32_t widest_array = 0;
  const auto unique = [&seen](const std::string& base) {
    const int n = ++seen[base];
    if (n == 1) return base;
    const bool ends_in_digit = !base.empty() && base.back() >= '0' && base.back() <= '9';
    return base + (ends_in_digit ? "_" : "") + std::to_string(n);
  };
  for (std::uint32_t index = 0; index < fields_.size(); ++index) {
    const InputField& f = fields_[index];
    Entry e;
    e.field = index;
    e.control = static_cast<std::uint32_t>(controls_.size());
    if (f.array) {
      if (f.bit_size <= 32 && f.usage_count() <= kMaxArrayControls) {
        e.kind = Kind::kArray;
        e.control = static_cast<std::uint32_t>(array_controls_.size());
        for (const UsageSpan& s : f.usages)
          for (std::uint32_t i = 0; i < s.size(); ++i) {
            const Usage u = s.first + i;
            if (usage_id(u) == 0) {  // "no event": names nothing
              array_controls_.push_back(kNoControl);
              continue;
            }
            array_controls_.push_back(static_cast<std::uint32_t>(controls_.size()));
            controls_.push_back({unique(usage_control_name(u)), false});
          }
        e.controls = static_cast<std::uint32_t>(array_controls_.size()) - e.control;
        widest_array = std::max(widest_array, e.controls);
      }
    } else if (f.bit_size <= 32) {
      if (is_hat(f.usage)) {
        e.kind = Kind::kHat;
        controls_.push_back({unique("hat_x"), true});
        controls_.push_back({unique("hat_y"), true});
        e.controls = 2;
      } else {
        e.kind = is_bipolar_axis(f.usage) ? Kind::kAxis : Kind::kUnipolar;
        controls_.push_back({unique(usage_control_name(f.usage)), e.kind == Kind::kAxis});
        e.controls = 1;
      }
    }
    if (e.kind != Kind::kOpaque) in_order.push_back(e);
  }
  entries_.reserve(in_order.size());
  for (std::uint32_t id = 0; id <= 255; ++id) {
    first_entry_[id] = static_cast<std::uint32_t>(entries_.size());
    for (const Entry& e : in_order)
      if (fields_[e.field].report_id == id) entries_.push_back(e);
  }
  first_entry_[256] = static_cast<std::uint32_t>(entries_.size());
  values_.assign(controls_.size(), std::numeric_limits<double>::quiet_NaN());
  pressed_.assign(widest_array, 0);
}

void ReportDecoder::reset() noexcept { std::fill(values_.begin(), values_.end(), std::numeric_limits<double>::quiet_NaN()); }

void ReportDecoder::set(std::uint32_t control, double value, ControlSink& sink, std::int64_t arrived_ns) noexcept {
  // NaN (never set) compares unequal, so the first value always posts.
  if (values_[control] == value) return;
  values_[control] = value;
  sink.post(controls_[control].name, value, controls_[control].bipolar, arrived_ns);
}

bool ReportDecoder::decode(std::span<const std::uint8_t> report, ControlSink& sink, std::int64_t arrived_ns) noexcept {
  if (report.empty()) return false;
  std::uint8_t id = 0;
  if (numbered_) {
    id = report[0];
    report = report.subspan(1);
  }
  const std::uint32_t begin = first_entry_[id];
  const std::uint32_t end = first_entry_[id + 1];
  if (begin == end) return false;
  for (std::uint32_t k = begin; k < end; ++k) {
    const Entry& e = entries_[k];
    const InputField& f = fields_[e.field];
    const std::int64_t lo = f.logical_minimum;
    const std::int64_t hi = f.logical_maximum;
    if (e.kind == Kind::kArray) {
      std::fill_n(pressed_.begin(), e.controls, std::uint8_t{0});
      bool complete = true;
      for (std::uint32_t slot = 0; slot < f.count; ++slot) {
        std::int64_t v = 0;
        if (!extract(report, std::uint64_t{f.bit_offset} + std::uint64_t{slot} * f.bit_size, f.bit_size, f.is_signed(), &v)) {
          complete = false;
          break;
        }
        if (v >= lo && v <= hi && v - lo < e.controls) pressed_[static_cast<std::size_t>(v - lo)] = 1;
      }
      if (!complete) continue;
      for (std::uint32_t i = 0; i < e.controls; ++i)
        if (const std::uint32_t c = array_controls_[e.control + i]; c != kNoControl)
          set(c, pressed_[i] != 0 ? 1.0 : 0.0, sink, arrived_ns);
      continue;
    }
    std::int64_t raw = 0;
    if (!extract(report, f.bit_offset, f.bit_size, f.is_signed(), &raw)) continue;
    switch (e.kind) {
      case Kind::kHat: {
        double x = 0.0;
        double y = 0.0;
        if (raw >= lo && raw <= hi) {
          const double angle = 2.0 * std::numbers::pi * static_cast<double>(raw - lo) / static_cast<double>(hi - lo + 1);
          x = static_cast<double>(std::lround(std::sin(angle)));
          y = -static_cast<double>(std::lround(std::cos(angle)));
          if (y == 0.0) y = 0.0;  // no -0
        }
        set(e.control, x, sink, arrived_ns);
        set(e.control + 1, y, sink, arrived_ns);
        break;
      }
      case Kind::kAxis: {
        if ((raw < lo || raw > hi) && f.null_state) break;  // no position: keep the last one
        raw = std::clamp(raw, lo, hi);
        const std::int64_t rest = rest_of(lo, hi);
        double v = 0.0;
        if (raw > rest) v = static_cast<double>(raw - rest) / static_cast<double>(hi - rest);
        if (raw < rest) v = -static_cast<double>(rest - raw) / static_cast<double>(rest - lo);
        set(e.control, v, sink, arrived_ns);
        break;
      }
      case Kind::kUnipolar: {
        if ((raw < lo || raw > hi) && f.null_state) break;
        raw = std::clamp(raw, lo, hi);
        const double v = hi == lo ? 0.0 : static_cast<double>(raw - lo) / static_cast<double>(hi - lo);
        set(e.control, v, sink, arrived_ns);
        break;
      }
      default: break;
    }
  }
  return true;
}

}  // namespace avar::inputs::hid
