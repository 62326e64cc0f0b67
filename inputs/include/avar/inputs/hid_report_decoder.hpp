#pragma once
// Input reports of a HID device as named, normalised controls (input_source.hpp), from the layout
// parse_report_descriptor() found. Pure: no I/O, no clock.
//
// Control names, from the HID usage tables:
//  - Generic Desktop X, Y, Z, Rx, Ry, Rz: `x y z rx ry rz`, bipolar -1..1. The logical extent is
//    centred on its rest value floor((min + max + 1) / 2) (128 for 0..255, 0 for -127..127) and
//    each half scaled on its own, so rest reads 0 and both ends read exactly -1 and 1;
//  - Slider, Dial, Wheel: `slider dial wheel`, unipolar 0..1 over the logical extent;
//  - Hat Switch: two bipolar axes `hat_x hat_y`, each -1, 0 or 1. Position 0 is up, positions
//    go clockwise in equal steps over the logical extent (8 positions: 45° each); up reads
//    hat_y = -1 (the HID and Linux convention, like the stick's y), right reads hat_x = 1. A value
//    outside the extent (the null state) reads centred (0, 0);
//  - Button page: `button1 .. buttonN` (the usage id), unipolar 0/1 (over the extent for analogue
//    buttons);
//  - anything else: `usage_PPPP_UUUU` (page and id in upper-case hex), unipolar.
// Names that repeat get a count: `x`, `x2`, `x3`; a name ending in a digit gets `_2`, `_3`
// (`usage_FF00_0021_2`). Array fields (a list of pressed usages) give one 0/1 control per usage
// they can name, usage id 0 ("none") left out; arrays naming more than kMaxArrayControls usages
// (whole keyboard or consumer pages) give none. Relative fields are normalised like absolute ones.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "avar/inputs/hid_report_descriptor.hpp"
#include "avar/inputs/input_source.hpp"

namespace avar::inputs::hid {

inline constexpr std::uint32_t kMaxArrayControls = 1024;

struct HidControl {
  std::string name;
  bool bipolar = false;  ///< -1..1, else 0..1
};

/// The base control name of a usage (before duplicates are numbered): "x", "button3",
/// "usage_FF00_0021"; the hat switch gives "hat" (its controls: hat_x, hat_y).
std::string usage_control_name(Usage usage);

class ReportDecoder {
 public:
  /// Names every control of `descriptor`'s input reports. Allocates; not real-time.
  explicit ReportDecoder(const ReportDescriptor& descriptor);

  /// Every control the reports carry, in descriptor order (a hat: hat_x then hat_y).
  const std::vector<HidControl>& controls() const noexcept { return controls_; }
  /// Each control's latest value, indexed like controls(); NaN until a report carried it.
  std::span<const double> values() const noexcept { return values_; }
  /// Bytes of the longest input report, the id byte included when numbered.
  std::size_t max_report_bytes() const noexcept { return max_report_bytes_; }

  /// Decodes one input report as the device sent it (first byte the report id when the
  /// descriptor is numbered) and posts to `sink` each control whose value changed since the last
  /// report (every control the first time). Fields that do not fit in a short report are left
  /// alone. Returns false, posting nothing, for an empty report or an unknown report id.
  /// Real-time safe: no allocation, no exception, no lock; one thread at a time.
  bool decode(std::span<const std::uint8_t> report, ControlSink& sink, std::int64_t arrived_ns) noexcept;

  /// Forgets the latest values: the next report posts every control again.
  void reset() noexcept;

 private:
  enum class Kind : std::uint8_t { kAxis, kUnipolar, kHat, kArray, kOpaque };
  struct Entry {
    std::uint32_t field = 0;  ///< index in fields_
    Kind kind = Kind::kOpaque;
    std::uint32_t control = 0;   ///< first control (hat: x then y); array: first index in array_controls_
    std::uint32_t controls = 0;  ///< array: usages it names
  };
  static constexpr std::uint32_t kNoControl = 0xFFFFFFFF;

  void add_control(std::string base, bool bipolar);
  void set(std::uint32_t control, double value, ControlSink& sink, std::int64_t arrived_ns) noexcept;

  std::vector<InputField> fields_;
  std::vector<Entry> entries_;           ///< grouped by report id
  std::uint32_t first_entry_[257] = {};  ///< entries of report id r: [first_entry_[r], first_entry_[r + 1])
  bool numbered_ = false;
  std::vector<HidControl> controls_;
  std::vector<double> values_;
  std::vector<std::uint32_t> array_controls_;  ///< per array usage: its control, or kNoControl (usage id 0)
  std::vector<std::uint8_t> pressed_;          ///< scratch for array fields, sized once
  std::size_t max_report_bytes_ = 0;
};

}  // namespace avar::inputs::hid
