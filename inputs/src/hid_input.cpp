#include "avar/inputs/hid_input.hpp"

#include <hidapi/hidapi.h>

#include <atomic>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>

#include "avar/core/monotonic_clock.hpp"
#include "avar/inputs/hid_report_decoder.hpp"

namespace avar::inputs {

namespace {

constexpr std::chrono::milliseconds kReadTimeout{50};
// Room beyond the longest report the descriptor declares, for devices that send longer ones
// (hidapi truncates a report to the buffer).
constexpr std::size_t kReportSlack = 64;
constexpr std::size_t kMaxDescriptorBytes = 4096;  // HID_MAX_DESCRIPTOR_SIZE in Linux

std::string narrow(const wchar_t* w) {
  // hidapi's strings are wchar_t (UTF-32 on Linux): encoded as UTF-8.
  std::string out;
  if (w == nullptr) return out;
  for (; *w != 0; ++w) {
    // wchar_t, not a signed char (clang-tidy 14 mistakes it for one).
    const std::uint32_t c = static_cast<std::make_unsigned_t<wchar_t>>(*w);  // NOLINT(bugprone-signed-char-misuse)
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

void init_hidapi() {
  static std::once_flag once;
  static int result = 0;
  std::call_once(once, [] { result = hid_init(); });
  if (result != 0) throw std::runtime_error("hidapi: cannot initialise (hid_init failed): " + narrow(hid_error(nullptr)));
}

bool parse_hex_id(std::string_view text, std::uint16_t* id) {
  if (text.empty() || text.size() > 4) return false;
  std::uint32_t v = 0;
  for (const char c : text) {
    int d = -1;
    if (c >= '0' && c <= '9') d = c - '0';
    if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
    if (d < 0) return false;
    v = v * 16 + static_cast<std::uint32_t>(d);
  }
  *id = static_cast<std::uint16_t>(v);
  return true;
}

class HidapiReader final : public HidReportReader {
 public:
  explicit HidapiReader(hid_device* device) : device_(device) {}
  ~HidapiReader() override { hid_close(device_); }
  HidapiReader(const HidapiReader&) = delete;
  HidapiReader& operator=(const HidapiReader&) = delete;

  int read(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) noexcept override {
    return hid_read_timeout(device_, buffer.data(), buffer.size(), static_cast<int>(timeout.count()));
  }
  hid_device* device() const noexcept { return device_; }

 private:
  hid_device* device_;
};

// Gamepads first: Generic Desktop Joystick (4), Game Pad (5), Multi-axis Controller (8).
bool is_game_controller(const HidDeviceInfo& d) {
  return d.usage_page == hid::kGenericDesktopPage && (d.usage == 0x04 || d.usage == 0x05 || d.usage == 0x08);
}

class HidInputSource final : public InputSource {
 public:
  explicit HidInputSource(HidDeviceSpec spec) : spec_(std::move(spec)) {}
  ~HidInputSource() override { stop(); }
  HidInputSource(const HidInputSource&) = delete;
  HidInputSource& operator=(const HidInputSource&) = delete;

  void start(ControlSink& sink) override {
    if (owned_) throw std::logic_error("HID input " + wanted() + " started twice");
    const std::vector<HidDeviceInfo> devices = enumerate_hid_devices();
    if (devices.empty())
      throw std::runtime_error("hidapi: no HID devices on this machine (looking for " + wanted() +
                               "); is the device plugged in, and may this user read /dev/hidraw*?");
    const HidDeviceInfo* chosen = nullptr;
    for (const HidDeviceInfo& d : devices) {
      if (d.vendor_id != spec_.vendor_id || d.product_id != spec_.product_id) continue;
      if (!spec_.serial.empty() && d.serial != spec_.serial) continue;
      if (chosen == nullptr || (!is_game_controller(*chosen) && is_game_controller(d))) chosen = &d;
    }
    if (chosen == nullptr) throw std::runtime_error("no HID device " + wanted() + " (found: " + list_hid_devices(devices) + ")");

    hid_device* device = hid_open_path(chosen->path.c_str());
    if (device == nullptr)
      throw std::runtime_error("hidapi: cannot open HID " + wanted() + " at " + chosen->path + ": " + narrow(hid_error(nullptr)) +
                               " (permissions? a udev rule giving this user " + chosen->path + ")");
    auto reader = std::make_unique<HidapiReader>(device);
    const std::string where = "HID " + wanted() + " at " + chosen->path;
    std::vector<std::uint8_t> bytes;
#if HID_API_VERSION >= HID_API_MAKE_VERSION(0, 14, 0)
    bytes.resize(kMaxDescriptorBytes);
    const int n = hid_get_report_descriptor(device, bytes.data(), bytes.size());
    if (n < 0) throw std::runtime_error(where + ": cannot read its report descriptor: " + narrow(hid_error(device)));
    bytes.resize(static_cast<std::size_t>(n));
#else
    bytes = read_hidraw_report_descriptor(chosen->path);
#endif
    hid::ReportDescriptor layout;
    try {
      layout = hid::parse_report_descriptor(bytes);
    } catch (const hid::HidDescriptorError& e) {
      throw std::runtime_error(where + ": " + e.what());
    }
    if (layout.fields.empty()) throw std::runtime_error(where + ": its report descriptor declares no input controls");
    std::string description = "HID " + hid_ids(chosen->vendor_id, chosen->product_id);
    if (!chosen->product.empty()) description += " " + chosen->product;
    owned_ = std::make_unique<HidReportPump>(layout, std::move(reader), description);
    owned_->start(sink);
    pump_.store(owned_.get(), std::memory_order_release);
  }

  void stop() noexcept override {
    if (HidReportPump* p = pump_.load(std::memory_order_acquire)) p->stop();
  }

  std::string describe() const override {
    if (const HidReportPump* p = pump_.load(std::memory_order_acquire)) return p->describe();
    return "HID " + wanted();
  }

  InputCounters counters() const noexcept override {
    if (const HidReportPump* p = pump_.load(std::memory_order_acquire)) return p->counters();
    return {};
  }

 private:
  std::string wanted() const {
    return hid_ids(spec_.vendor_id, spec_.product_id) + (spec_.serial.empty() ? "" : " serial " + spec_.serial);
  }

  HidDeviceSpec spec_;
  std::unique_ptr<HidReportPump> owned_;  // start()'s thread only
  std::atomic<HidReportPump*> pump_{nullptr};
};

}  // namespace

HidDeviceSpec parse_hid_device_spec(std::string_view spec) {
  const auto bad = [spec](const std::string& why) {
    return std::invalid_argument("HID device '" + std::string(spec) + "': " + why +
                                 "; expected VID:PID or VID:PID:SERIAL with hex ids, e.g. hid:054c:09cc");
  };
  HidDeviceSpec out;
  const std::size_t first = spec.find(':');
  if (first == std::string_view::npos) throw bad("no ':' between vendor and product id");
  const std::size_t second = spec.find(':', first + 1);
  const std::string_view vid = spec.substr(0, first);
  const std::string_view pid =
      spec.substr(first + 1, second == std::string_view::npos ? std::string_view::npos : second - first - 1);
  if (!parse_hex_id(vid, &out.vendor_id)) throw bad("vendor id '" + std::string(vid) + "' is not 1 to 4 hex digits");
  if (!parse_hex_id(pid, &out.product_id)) throw bad("product id '" + std::string(pid) + "' is not 1 to 4 hex digits");
  if (second != std::string_view::npos) {
    out.serial = std::string(spec.substr(second + 1));
    if (out.serial.empty()) throw bad("empty serial after the second ':'");
  }
  return out;
}

std::string hid_ids(std::uint16_t vendor_id, std::uint16_t product_id) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04x:%04x", vendor_id, product_id);
  return buf;
}

std::vector<HidDeviceInfo> enumerate_hid_devices() {
  init_hidapi();
  std::vector<HidDeviceInfo> out;
  hid_device_info* all = hid_enumerate(0, 0);
  for (const hid_device_info* d = all; d != nullptr; d = d->next) {
    HidDeviceInfo info;
    info.path = d->path != nullptr ? d->path : "";
    info.vendor_id = d->vendor_id;
    info.product_id = d->product_id;
    info.serial = narrow(d->serial_number);
    info.manufacturer = narrow(d->manufacturer_string);
    info.product = narrow(d->product_string);
    info.usage_page = d->usage_page;
    info.usage = d->usage;
    info.interface_number = d->interface_number;
    out.push_back(std::move(info));
  }
  hid_free_enumeration(all);
  return out;
}

std::string list_hid_devices(const std::vector<HidDeviceInfo>& devices) {
  std::string out;
  std::string previous;
  for (const HidDeviceInfo& d : devices) {
    std::string entry = hid_ids(d.vendor_id, d.product_id);
    if (!d.product.empty()) entry += " " + d.product;
    if (!d.serial.empty()) entry += " serial " + d.serial;
    if (entry == previous) continue;  // one line per device, not per interface
    out += (out.empty() ? "" : ", ") + entry;
    previous = std::move(entry);
  }
  return out;
}

std::vector<std::uint8_t> read_hidraw_report_descriptor(const std::string& hidraw_path) {
  const std::size_t slash = hidraw_path.find_last_of('/');
  const std::string node = slash == std::string::npos ? hidraw_path : hidraw_path.substr(slash + 1);
  if (node.rfind("hidraw", 0) != 0)
    throw std::runtime_error("HID device path '" + hidraw_path +
                             "' is not a hidraw node (/dev/hidrawN); the report descriptor is read from sysfs for hidraw only");
  const std::string file = "/sys/class/hidraw/" + node + "/device/report_descriptor";
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the HID report descriptor " + file);
  std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.empty() || bytes.size() > kMaxDescriptorBytes)
    throw std::runtime_error("HID report descriptor " + file + " has " + std::to_string(bytes.size()) + " bytes; expected 1.." +
                             std::to_string(kMaxDescriptorBytes));
  return bytes;
}

struct HidReportPump::State {
  State(const hid::ReportDescriptor& descriptor, std::unique_ptr<HidReportReader> r, std::string d)
      : decoder(descriptor), reader(std::move(r)), description(std::move(d)), buffer(decoder.max_report_bytes() + kReportSlack) {}

  void run(ControlSink& sink) noexcept {
    while (running.load(std::memory_order_acquire)) {
      const int n = reader->read(buffer, kReadTimeout);
      if (n < 0) {
        gone.store(true, std::memory_order_release);
        return;
      }
      if (n == 0) continue;
      const std::int64_t arrived = monotonic_ns();
      messages.fetch_add(1, std::memory_order_relaxed);
      const auto length = std::min(static_cast<std::size_t>(n), buffer.size());
      if (!decoder.decode(std::span(buffer.data(), length), sink, arrived)) ignored.fetch_add(1, std::memory_order_relaxed);
    }
  }

  hid::ReportDecoder decoder;
  std::unique_ptr<HidReportReader> reader;
  std::string description;
  std::vector<std::uint8_t> buffer;
  std::thread thread;
  std::atomic<bool> running{false};
  std::atomic<bool> gone{false};
  std::atomic<std::uint64_t> messages{0};
  std::atomic<std::uint64_t> ignored{0};
};

HidReportPump::HidReportPump(const hid::ReportDescriptor& descriptor, std::unique_ptr<HidReportReader> reader,
                             std::string description)
    : state_(std::make_unique<State>(descriptor, std::move(reader), std::move(description))) {}

HidReportPump::~HidReportPump() { stop(); }

void HidReportPump::start(ControlSink& sink) {
  if (state_->thread.joinable()) throw std::logic_error(state_->description + ": started twice");
  state_->running.store(true, std::memory_order_release);
  State* s = state_.get();
  state_->thread = std::thread([s, &sink] { s->run(sink); });
}

void HidReportPump::stop() noexcept {
  state_->running.store(false, std::memory_order_release);
  if (state_->thread.joinable()) state_->thread.join();
}

std::string HidReportPump::describe() const { return state_->description + (disconnected() ? " (disconnected)" : ""); }

InputCounters HidReportPump::counters() const noexcept {
  return {state_->messages.load(std::memory_order_relaxed), state_->ignored.load(std::memory_order_relaxed)};
}

bool HidReportPump::disconnected() const noexcept { return state_->gone.load(std::memory_order_acquire); }

std::vector<std::string> HidReportPump::control_names() const {
  std::vector<std::string> names;
  for (const hid::HidControl& c : state_->decoder.controls()) names.push_back(c.name);
  return names;
}

std::unique_ptr<InputSource> make_hid_input(std::string_view spec) {
  return std::make_unique<HidInputSource>(parse_hid_device_spec(spec));
}

}  // namespace avar::inputs
