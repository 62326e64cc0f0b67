#include "avar/firmware_iface/libusb_control_transport.hpp"

#include <libusb-1.0/libusb.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace avar::firmware_iface {

struct LibusbControlTransport::Handles {
  libusb_context* context = nullptr;
  libusb_device_handle* device = nullptr;
};

namespace {

std::string hex4(std::uint16_t v) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%04X", v);
  return text;
}

/// The serial number string of an opened device, or empty.
std::string serial_of(libusb_device_handle* handle, std::uint8_t index) {
  if (index == 0) return {};
  unsigned char text[256];
  const int n = libusb_get_string_descriptor_ascii(handle, index, text, sizeof text);
  return n > 0 ? std::string(reinterpret_cast<const char*>(text), static_cast<std::size_t>(n)) : std::string{};
}

}  // namespace

std::string describe_found(const std::vector<UsbDeviceFound>& found) {
  if (found.empty()) return "none";
  std::string out;
  for (const UsbDeviceFound& f : found) {
    if (!out.empty()) out += ", ";
    out += (f.serial.empty() ? "a device whose serial could not be read" : f.serial) + " (" + hex4(f.product_id) + ")";
    if (!f.problem.empty()) out += ": " + f.problem;
  }
  return out;
}

LibusbControlTransport::LibusbControlTransport(UsbDeviceQuery query)
    : query_(std::move(query)), handles_(std::make_unique<Handles>()) {
  if (const int r = libusb_init(&handles_->context); r != 0) {
    handles_->context = nullptr;
    throw std::runtime_error(std::string("libusb: no USB on this machine (libusb_init: ") + libusb_error_name(r) + ")");
  }
  try {
    open();
  } catch (...) {
    libusb_exit(handles_->context);
    throw;
  }
}

LibusbControlTransport::~LibusbControlTransport() {
  close();
  if (handles_->context) libusb_exit(handles_->context);
}

void LibusbControlTransport::close() noexcept {
  if (handles_->device) libusb_close(handles_->device);
  handles_->device = nullptr;
}

void LibusbControlTransport::open() {
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(handles_->context, &list);
  if (count < 0)
    throw std::runtime_error(std::string("libusb: no USB on this machine (listing devices: ") +
                             libusb_error_name(static_cast<int>(count)) + ")");
  struct FreeList {
    libusb_device** list;
    ~FreeList() { libusb_free_device_list(list, 1); }
  } free_list{list};

  const std::string& who = query_.device_name;
  std::vector<UsbDeviceFound> found;
  struct Match {
    libusb_device_handle* handle;
    std::uint16_t product_id;
    std::string serial;
  };
  std::vector<Match> matches;
  for (ssize_t i = 0; i < count; ++i) {
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(list[i], &desc) != 0 || desc.idVendor != query_.vendor_id) continue;
    if (std::find(query_.product_ids.begin(), query_.product_ids.end(), desc.idProduct) == query_.product_ids.end()) continue;
    libusb_device_handle* handle = nullptr;
    if (const int r = libusb_open(list[i], &handle); r != 0) {
      found.push_back({desc.idProduct, {}, std::string("cannot open it: ") + libusb_error_name(r)});
      continue;
    }
    const std::string serial = serial_of(handle, desc.iSerialNumber);
    found.push_back({desc.idProduct, serial, {}});
    if (query_.serial.empty() || serial == query_.serial) matches.push_back({handle, desc.idProduct, serial});
    else libusb_close(handle);
  }
  const auto close_all = [&] {
    for (const Match& m : matches) libusb_close(m.handle);
  };
  if (matches.empty()) {
    const std::string which = query_.serial.empty() ? "no " + who : "no " + who + " with serial " + query_.serial;
    const bool unreadable = std::any_of(found.begin(), found.end(), [](const UsbDeviceFound& f) { return !f.problem.empty(); });
    throw std::runtime_error(which + " on USB (found: " + describe_found(found) + ")" +
                             (unreadable ? "; a device that cannot be opened usually lacks a udev rule granting access" : ""));
  }
  if (matches.size() > 1) {
    close_all();
    throw std::runtime_error("several " + who + "s on USB (found: " + describe_found(found) + "); name one by its serial number");
  }
  handles_->device = matches[0].handle;
  product_id_ = matches[0].product_id;
  // From now on this is the device: a reopen after an unplug finds it again by its serial.
  query_.serial = matches[0].serial;
  name_ = "USB (serial " + query_.serial + ")";
}

Status LibusbControlTransport::control(const UsbSetup& setup, std::span<std::uint8_t> data, std::chrono::milliseconds timeout,
                                       std::size_t* transferred) noexcept {
  *transferred = 0;
  if (!handles_->device) return Status::io_error;
  const int r =
      libusb_control_transfer(handles_->device, setup.request_type, setup.request, setup.value, setup.index, data.data(),
                              setup.length, static_cast<unsigned>(std::max<long long>(1, timeout.count())));
  if (r >= 0) {
    *transferred = static_cast<std::size_t>(r);
    return Status::ok;
  }
  switch (r) {
    case LIBUSB_ERROR_TIMEOUT: return Status::timeout;
    case LIBUSB_ERROR_PIPE: return Status::bad_data;  // the device stalled: it refuses the request
    default: return Status::io_error;
  }
}

Status LibusbControlTransport::reopen() noexcept {
  close();
  try {
    open();
    return Status::ok;
  } catch (...) {
    return Status::io_error;
  }
}

}  // namespace avar::firmware_iface
