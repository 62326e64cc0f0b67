#include "avar/inputs/hid_report_descriptor.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "avar/core/byte_order.hpp"

namespace avar::inputs::hid {

HidDescriptorError::HidDescriptorError(std::size_t offset, const std::string& problem)
    : std::runtime_error("HID report descriptor, byte " + std::to_string(offset) + ": " + problem), offset_(offset) {}

std::uint32_t InputField::usage_count() const noexcept {
  std::uint32_t n = 0;
  for (const UsageSpan& s : usages) n += s.size();
  return n;
}

Usage InputField::array_usage(std::int64_t value) const noexcept {
  if (value < logical_minimum || value > logical_maximum) return 0;
  std::int64_t index = value - logical_minimum;
  for (const UsageSpan& s : usages) {
    if (index < s.size()) return s.first + static_cast<Usage>(index);
    index -= s.size();
  }
  return 0;
}

const InputReportLayout* ReportDescriptor::report(std::uint8_t id) const noexcept {
  for (const InputReportLayout& r : reports)
    if (r.report_id == id) return &r;
  return nullptr;
}

std::size_t ReportDescriptor::max_report_bytes() const noexcept {
  std::size_t most = 0;
  for (const InputReportLayout& r : reports) most = std::max(most, r.bytes());
  return most + (numbered ? 1 : 0);
}

namespace {

enum ItemType : std::uint8_t { kMain = 0, kGlobal = 1, kLocal = 2, kReserved = 3 };

enum MainTag : std::uint8_t { kInput = 0x8, kOutput = 0x9, kCollection = 0xA, kFeature = 0xB, kEndCollection = 0xC };
enum GlobalTag : std::uint8_t {
  kUsagePage = 0x0,
  kLogicalMinimum = 0x1,
  kLogicalMaximum = 0x2,
  kPhysicalMinimum = 0x3,
  kPhysicalMaximum = 0x4,
  kUnitExponent = 0x5,
  kUnit = 0x6,
  kReportSize = 0x7,
  kReportId = 0x8,
  kReportCount = 0x9,
  kPush = 0xA,
  kPop = 0xB,
};
enum LocalTag : std::uint8_t { kUsage = 0x0, kUsageMinimum = 0x1, kUsageMaximum = 0x2, kDelimiter = 0xA };

// Input item flag bits (HID 1.11 §6.2.2.5).
constexpr std::uint32_t kConstantFlag = 1u << 0;
constexpr std::uint32_t kVariableFlag = 1u << 1;
constexpr std::uint32_t kRelativeFlag = 1u << 2;
constexpr std::uint32_t kNullStateFlag = 1u << 6;

constexpr std::size_t kMaxPushDepth = 32;
constexpr std::size_t kMaxCollectionDepth = 64;
constexpr std::uint8_t kLongItemPrefix = 0xFE;

const char* item_name(std::uint8_t type, std::uint8_t tag) {
  static const char* const main_names[16] = {nullptr,          nullptr, nullptr, nullptr,  nullptr,      nullptr,
                                             nullptr,          nullptr, "Input", "Output", "Collection", "Feature",
                                             "End Collection", nullptr, nullptr, nullptr};
  static const char* const global_names[16] = {"Usage Page",
                                               "Logical Minimum",
                                               "Logical Maximum",
                                               "Physical Minimum",
                                               "Physical Maximum",
                                               "Unit Exponent",
                                               "Unit",
                                               "Report Size",
                                               "Report ID",
                                               "Report Count",
                                               "Push",
                                               "Pop",
                                               nullptr,
                                               nullptr,
                                               nullptr,
                                               nullptr};
  static const char* const local_names[16] = {"Usage",
                                              "Usage Minimum",
                                              "Usage Maximum",
                                              "Designator Index",
                                              "Designator Minimum",
                                              "Designator Maximum",
                                              nullptr,
                                              "String Index",
                                              "String Minimum",
                                              "String Maximum",
                                              "Delimiter",
                                              nullptr,
                                              nullptr,
                                              nullptr,
                                              nullptr,
                                              nullptr};
  const char* name = nullptr;
  if (type == kMain) name = main_names[tag];
  if (type == kGlobal) name = global_names[tag];
  if (type == kLocal) name = local_names[tag];
  return name != nullptr ? name : "reserved item";
}

std::string hex(std::uint32_t v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
  return buf;
}

struct GlobalState {
  std::uint16_t usage_page = 0;
  std::int32_t logical_minimum = 0;
  std::int32_t logical_maximum = 0;
  std::int32_t physical_minimum = 0;
  std::int32_t physical_maximum = 0;
  // Unsigned readings of the maxima, for extents written without their sign byte.
  std::uint32_t logical_maximum_unsigned = 0;
  std::uint32_t physical_maximum_unsigned = 0;
  std::uint32_t report_size = 0;
  std::uint32_t report_count = 0;
  std::uint8_t report_id = 0;
};

// A Usage, or a Usage Minimum/Maximum pair, as written: resolved against the usage page in force
// at the main item unless written as an extended (4-byte) usage.
struct PendingUsage {
  std::uint32_t first = 0;
  std::uint32_t last = 0;
  bool first_extended = false;
  bool last_extended = false;
  std::size_t offset = 0;  // the item that completed it
};

struct PendingBound {
  std::uint32_t value = 0;
  bool extended = false;
  std::size_t offset = 0;
};

struct LocalState {
  std::vector<PendingUsage> usages;
  std::optional<PendingBound> minimum;
  std::optional<PendingBound> maximum;
  bool in_delimiter = false;
  bool delimiter_taken = false;  // the open delimiter set already gave its usage
};

class Parser {
 public:
  explicit Parser(std::span<const std::uint8_t> d) : d_(d) {}

  ReportDescriptor run() {
    std::size_t pos = 0;
    while (pos < d_.size()) {
      const std::size_t at = pos;
      const std::uint8_t prefix = d_[pos];
      if (prefix == kLongItemPrefix) {
        if (d_.size() - pos < 3)
          fail(at, "long item header cut short (" + std::to_string(d_.size() - pos) +
                       " bytes left); expected 0xFE, a data size and a tag");
        const std::size_t size = d_[pos + 1];
        if (d_.size() - pos - 3 < size)
          fail(at, "long item of " + std::to_string(size) + " data bytes with only " + std::to_string(d_.size() - pos - 3) +
                       " left; expected the whole item");
        pos += 3 + size;  // long items carry no standard meaning: skipped
        continue;
      }
      const std::size_t size = (prefix & 3u) == 3u ? 4 : (prefix & 3u);
      const auto type = static_cast<std::uint8_t>((prefix >> 2) & 3u);
      const auto tag = static_cast<std::uint8_t>(prefix >> 4);
      if (d_.size() - pos - 1 < size)
        fail(at, std::string("item ") + hex(prefix, 2) + " (" + item_name(type, tag) + ") needs " + std::to_string(size) +
                     " data bytes, only " + std::to_string(d_.size() - pos - 1) + " left; expected a complete item");
      const std::uint32_t value = get_le(d_.data() + pos + 1, size);
      // Sign extension from the item's own size: (v ^ sign) - sign.
      std::int32_t signed_value = static_cast<std::int32_t>(value);
      if (size == 1) signed_value = static_cast<std::int32_t>(value ^ 0x80u) - 0x80;
      if (size == 2) signed_value = static_cast<std::int32_t>(value ^ 0x8000u) - 0x8000;
      pos += 1 + size;
      item_ = Item{at, type, tag, size, value, signed_value};
      switch (type) {
        case kMain: main_item(); break;
        case kGlobal: global_item(); break;
        case kLocal: local_item(); break;
        default: break;  // reserved item type: no meaning defined, skipped
      }
    }
    if (collection_depth_ != 0)
      fail(d_.size(), "the descriptor ends inside " + std::to_string(collection_depth_) +
                          " open collection(s); expected End Collection for each");
    return std::move(out_);
  }

 private:
  struct Item {
    std::size_t offset = 0;
    std::uint8_t type = 0;
    std::uint8_t tag = 0;
    std::size_t size = 0;
    std::uint32_t value = 0;
    std::int32_t signed_value = 0;
  };

  [[noreturn]] static void fail(std::size_t offset, const std::string& problem) { throw HidDescriptorError(offset, problem); }

  void global_item() {
    switch (item_.tag) {
      case kUsagePage:
        if (item_.value > 0xFFFF) fail(item_.offset, "usage page " + hex(item_.value, 4) + "; expected a 16-bit page");
        g_.usage_page = static_cast<std::uint16_t>(item_.value);
        break;
      case kLogicalMinimum: g_.logical_minimum = item_.signed_value; break;
      case kLogicalMaximum:
        g_.logical_maximum = item_.signed_value;
        g_.logical_maximum_unsigned = item_.value;
        break;
      case kPhysicalMinimum: g_.physical_minimum = item_.signed_value; break;
      case kPhysicalMaximum:
        g_.physical_maximum = item_.signed_value;
        g_.physical_maximum_unsigned = item_.value;
        break;
      case kUnitExponent:
      case kUnit: break;  // units do not change how values are normalised
      case kReportSize:
        if (item_.value > kMaxReportSize)
          fail(item_.offset,
               "report size " + std::to_string(item_.value) + " bits; expected at most " + std::to_string(kMaxReportSize));
        g_.report_size = item_.value;
        break;
      case kReportId:
        if (item_.value == 0 || item_.value > 0xFF)
          fail(item_.offset, "report id " + std::to_string(item_.value) + "; expected 1..255 (0 is reserved)");
        if (unnumbered_input_)
          fail(item_.offset,
               "a Report ID after input data that had none; expected every report of a numbered "
               "descriptor to follow a Report ID");
        g_.report_id = static_cast<std::uint8_t>(item_.value);
        out_.numbered = true;
        break;
      case kReportCount: g_.report_count = item_.value; break;
      case kPush:
        if (stack_.size() >= kMaxPushDepth)
          fail(item_.offset,
               "Push nested " + std::to_string(kMaxPushDepth + 1) + " deep; expected at most " + std::to_string(kMaxPushDepth));
        stack_.push_back(g_);
        break;
      case kPop:
        if (stack_.empty()) fail(item_.offset, "Pop with nothing pushed; expected a Push before it");
        g_ = stack_.back();
        stack_.pop_back();
        break;
      default: fail(item_.offset, "unknown global item tag " + hex(item_.tag, 1) + "; expected one of HID 1.11's global items");
    }
  }

  void local_item() {
    const bool extended = item_.size == 4;
    switch (item_.tag) {
      case kUsage:
        if (take_usage()) l_.usages.push_back({item_.value, item_.value, extended, extended, item_.offset});
        break;
      case kUsageMinimum:
        l_.minimum = PendingBound{item_.value, extended, item_.offset};
        pair_range();
        break;
      case kUsageMaximum:
        l_.maximum = PendingBound{item_.value, extended, item_.offset};
        pair_range();
        break;
      case kDelimiter:
        if (item_.value == 1) {
          l_.in_delimiter = true;
          l_.delimiter_taken = false;
        } else {
          l_.in_delimiter = false;
        }
        break;
      default: break;  // designators and strings do not shape reports
    }
  }

  // Inside a delimiter set only the first usage counts (the alternatives name the same control).
  bool take_usage() {
    if (!l_.in_delimiter) return true;
    if (l_.delimiter_taken) return false;
    l_.delimiter_taken = true;
    return true;
  }

  void pair_range() {
    if (!l_.minimum || !l_.maximum) return;
    if (take_usage())
      l_.usages.push_back({l_.minimum->value, l_.maximum->value, l_.minimum->extended, l_.maximum->extended, item_.offset});
    l_.minimum.reset();
    l_.maximum.reset();
  }

  Usage resolve(std::uint32_t value, bool extended) const {
    return extended ? value : make_usage(g_.usage_page, static_cast<std::uint16_t>(value & 0xFFFF));
  }

  std::vector<UsageSpan> resolved_usages() const {
    std::vector<UsageSpan> spans;
    spans.reserve(l_.usages.size());
    for (const PendingUsage& p : l_.usages) {
      const UsageSpan s{resolve(p.first, p.first_extended), resolve(p.last, p.last_extended)};
      if (usage_page(s.first) != usage_page(s.last))
        fail(p.offset,
             "usage range " + hex(s.first, 8) + ".." + hex(s.last, 8) + " crosses usage pages; expected both ends on one page");
      if (usage_id(s.last) < usage_id(s.first))
        fail(p.offset, "usage maximum " + hex(usage_id(s.last), 2) + " below usage minimum " + hex(usage_id(s.first), 2) +
                           "; expected a range from low to high");
      spans.push_back(s);
    }
    return spans;
  }

  void main_item() {
    if (l_.minimum || l_.maximum)
      fail(item_.offset, std::string("a lone ") + (l_.minimum ? "Usage Minimum" : "Usage Maximum") + " before " +
                             item_name(kMain, item_.tag) + "; expected Usage Minimum and Usage Maximum in pairs");
    switch (item_.tag) {
      case kInput: input_item(); break;
      case kOutput:
      case kFeature:
        resolved_usages();  // checked, then dropped
        break;
      case kCollection: {
        if (collection_depth_ >= kMaxCollectionDepth)
          fail(item_.offset, "collections nested " + std::to_string(kMaxCollectionDepth + 1) + " deep; expected at most " +
                                 std::to_string(kMaxCollectionDepth));
        const std::vector<UsageSpan> spans = resolved_usages();
        if (collection_depth_ == 0 && out_.application == 0 && !spans.empty()) out_.application = spans.front().first;
        ++collection_depth_;
        break;
      }
      case kEndCollection:
        if (collection_depth_ == 0) fail(item_.offset, "End Collection with no open collection; expected a Collection before it");
        --collection_depth_;
        break;
      default:
        fail(item_.offset,
             "unknown main item tag " + hex(item_.tag, 1) + "; expected Input, Output, Feature, Collection or End Collection");
    }
    l_ = LocalState{};
  }

  InputReportLayout& report_layout(std::uint8_t id) {
    for (InputReportLayout& r : out_.reports)
      if (r.report_id == id) return r;
    out_.reports.push_back({id, 0});
    return out_.reports.back();
  }

  // Extents written as positive values without their sign byte (Logical Maximum 255 as one byte
  // 0xFF) read as negative; when the minimum is not negative they mean the unsigned value.
  static std::int64_t fix_maximum(std::int32_t minimum, std::int32_t maximum, std::uint32_t unsigned_maximum) {
    if (minimum >= 0 && maximum < minimum) return unsigned_maximum;
    return maximum;
  }

  void input_item() {
    const std::uint32_t flags = item_.value;
    const std::uint64_t bits = std::uint64_t{g_.report_size} * g_.report_count;
    const std::vector<UsageSpan> spans = resolved_usages();
    if (bits == 0) return;
    if (!out_.numbered) unnumbered_input_ = true;
    InputReportLayout& layout = report_layout(g_.report_id);
    const std::uint64_t end = std::uint64_t{layout.bits} + bits;
    if (end > kMaxReportBytes * 8)
      fail(item_.offset, "input report " + std::to_string(g_.report_id) + " grows to " + std::to_string(end) +
                             " bits (report count " + std::to_string(g_.report_count) + " x report size " +
                             std::to_string(g_.report_size) + "); expected at most " + std::to_string(kMaxReportBytes * 8));
    const std::uint32_t start = layout.bits;
    layout.bits = static_cast<std::uint32_t>(end);
    if ((flags & kConstantFlag) != 0 || spans.empty()) return;  // padding, or data nobody named

    const std::int64_t lmax = fix_maximum(g_.logical_minimum, g_.logical_maximum, g_.logical_maximum_unsigned);
    if (g_.logical_minimum > lmax)
      fail(item_.offset, "logical minimum " + std::to_string(g_.logical_minimum) + " above logical maximum " +
                             std::to_string(lmax) + "; expected minimum <= maximum");
    InputField f;
    f.report_id = g_.report_id;
    f.bit_size = g_.report_size;
    f.relative = (flags & kRelativeFlag) != 0;
    f.null_state = (flags & kNullStateFlag) != 0;
    f.logical_minimum = g_.logical_minimum;
    f.logical_maximum = lmax;
    f.physical_minimum = g_.physical_minimum;
    f.physical_maximum = fix_maximum(g_.physical_minimum, g_.physical_maximum, g_.physical_maximum_unsigned);
    if (f.physical_minimum == 0 && f.physical_maximum == 0) {  // HID 1.11: physical = logical when both are 0
      f.physical_minimum = f.logical_minimum;
      f.physical_maximum = f.logical_maximum;
    }
    if ((flags & kVariableFlag) == 0) {
      f.array = true;
      f.bit_offset = start;
      f.count = g_.report_count;
      f.usages = spans;
      out_.fields.push_back(std::move(f));
      return;
    }
    // A variable item: one field per count, each taking the next usage; the last usage repeats.
    std::size_t span = 0;
    std::uint32_t within = 0;
    for (std::uint32_t i = 0; i < g_.report_count; ++i) {
      f.bit_offset = start + i * g_.report_size;
      f.usage = spans[span].first + within;
      out_.fields.push_back(f);
      if (within + 1 < spans[span].size()) {
        ++within;
      } else if (span + 1 < spans.size()) {
        ++span;
        within = 0;
      }
    }
  }

  std::span<const std::uint8_t> d_;
  Item item_;
  GlobalState g_;
  LocalState l_;
  std::vector<GlobalState> stack_;
  std::size_t collection_depth_ = 0;
  bool unnumbered_input_ = false;
  ReportDescriptor out_;
};

}  // namespace

ReportDescriptor parse_report_descriptor(std::span<const std::uint8_t> descriptor) { return Parser(descriptor).run(); }

}  // namespace avar::inputs::hid
