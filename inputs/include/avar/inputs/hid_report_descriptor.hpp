#pragma once
// HID report descriptors (Device Class Definition for HID 1.11, §6.2.2): a pure parser that turns
// the descriptor a device sends into the layout of its input reports. No I/O; used once, when a
// device is opened (it allocates and throws), never per report.
//
// Covered: short items (main, global, local), long items (skipped), usage pages, extended 32-bit
// usages, report ids, logical/physical extents with sign extension (and the common positive
// extent written without its sign byte: Logical Minimum 0, Logical Maximum 0xFF in one byte),
// report size/count, usage minimum/maximum ranges, variable and array fields, constant padding,
// push/pop, collections, delimiters (first usage of each set), null state. Output and feature
// items are checked but leave no fields.
//
// Every read is bounds-checked: a malformed descriptor throws HidDescriptorError naming the byte
// offset of the offending item and what was expected, and never reads outside the span.

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace avar::inputs::hid {

/// A usage: page in the high 16 bits, usage id in the low 16 (HID's extended usage).
using Usage = std::uint32_t;
constexpr Usage make_usage(std::uint16_t page, std::uint16_t id) noexcept { return (Usage{page} << 16) | id; }
constexpr std::uint16_t usage_page(Usage u) noexcept { return static_cast<std::uint16_t>(u >> 16); }
constexpr std::uint16_t usage_id(Usage u) noexcept { return static_cast<std::uint16_t>(u & 0xFFFF); }

inline constexpr std::uint16_t kGenericDesktopPage = 0x01;
inline constexpr std::uint16_t kButtonPage = 0x09;
inline constexpr std::uint16_t kHatSwitch = 0x39;  ///< Generic Desktop usage

/// Longest input report accepted, in bytes after the report id (the largest USB HID transfer is
/// far smaller; a longer one is a malformed descriptor).
inline constexpr std::size_t kMaxReportBytes = 8192;
/// Largest Report Size accepted, in bits (field values wider than 32 bits produce no control).
inline constexpr std::uint32_t kMaxReportSize = 256;

/// A malformed descriptor. what(): "HID report descriptor, byte N: <found>; expected <what>".
class HidDescriptorError : public std::runtime_error {
 public:
  HidDescriptorError(std::size_t offset, const std::string& problem);
  /// Offset of the item's first byte in the descriptor.
  std::size_t offset() const noexcept { return offset_; }

 private:
  std::size_t offset_;
};

/// A run of consecutive usages, first..last inclusive (one Usage item: first == last).
struct UsageSpan {
  Usage first = 0;
  Usage last = 0;
  std::uint32_t size() const noexcept { return usage_id(last) - usage_id(first) + 1u; }
};

/// One data field of an input report.
///  - variable: one value, one usage (`usage`);
///  - array: `count` slots of `bit_size` bits, each holding a value v in the logical extent that
///    names the usage at index v - logical_minimum of `usages` (a value outside: no usage).
struct InputField {
  std::uint8_t report_id = 0;    ///< 0 when the descriptor has no report ids
  std::uint32_t bit_offset = 0;  ///< from the first bit after the report id byte (LSB first)
  std::uint32_t bit_size = 0;    ///< Report Size
  std::uint32_t count = 1;       ///< array slots; 1 for a variable
  bool array = false;
  bool relative = false;             ///< Input's Relative flag (a change, not a position)
  bool null_state = false;           ///< Input's Null State flag: values outside the logical extent mean "none"
  std::int64_t logical_minimum = 0;  ///< extents as written (a positive maximum read unsigned)
  std::int64_t logical_maximum = 0;
  std::int64_t physical_minimum = 0;  ///< equal to the logical extent when the descriptor gave none
  std::int64_t physical_maximum = 0;
  Usage usage = 0;                ///< variable
  std::vector<UsageSpan> usages;  ///< array, in index order
  /// Values of the field are signed (two's complement in bit_size bits) when the logical
  /// minimum is negative.
  bool is_signed() const noexcept { return logical_minimum < 0; }
  /// Usages an array field names (sum of its spans).
  std::uint32_t usage_count() const noexcept;
  /// The usage an array value names, or 0 when the value names none.
  Usage array_usage(std::int64_t value) const noexcept;
};

/// One input report: its id and length (data and padding, without the id byte).
struct InputReportLayout {
  std::uint8_t report_id = 0;
  std::uint32_t bits = 0;
  std::size_t bytes() const noexcept { return (bits + 7) / 8; }
};

struct ReportDescriptor {
  /// Every report starts with its report id byte (the descriptor has Report ID items).
  bool numbered = false;
  /// Data fields of all input reports, in descriptor order (constant fields are padding: left out).
  std::vector<InputField> fields;
  /// Input reports in the order their first field appears.
  std::vector<InputReportLayout> reports;
  /// Usage of the first top-level collection (e.g. Generic Desktop / Game Pad), 0 when none.
  Usage application = 0;

  /// The layout of the input report with this id, or nullptr.
  const InputReportLayout* report(std::uint8_t id) const noexcept;
  /// Bytes of the longest input report, the id byte included when numbered.
  std::size_t max_report_bytes() const noexcept;
};

/// Parses a whole descriptor. Throws HidDescriptorError (byte offset, found, expected) for a
/// truncated item, an unknown main or global item, a report id of 0, a report longer than
/// kMaxReportBytes, a Report Size above kMaxReportSize, an inverted or page-crossing usage range,
/// a lone Usage Minimum or Maximum, a logical minimum above the maximum, Pop without Push, an
/// unbalanced collection, input data before the first Report ID of a numbered descriptor.
ReportDescriptor parse_report_descriptor(std::span<const std::uint8_t> descriptor);

}  // namespace avar::inputs::hid
