#include "avar/sim/usb_device_host.hpp"

namespace avar::sim {

class UsbDeviceHost::Connection final : public firmware_iface::UsbControlTransport {
 public:
  explicit Connection(UsbDeviceHost& host) : host_(host) {}

  Status control(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::chrono::milliseconds,
                 std::size_t* transferred) noexcept override {
    *transferred = 0;
    std::lock_guard lock(host_.mutex_);
    if (!host_.plugged_) return Status::io_error;
    ++host_.transfers_;
    return host_.device_.control(setup, data, transferred);
  }

  Status reopen() noexcept override {
    std::lock_guard lock(host_.mutex_);
    return host_.plugged_ ? Status::ok : Status::io_error;
  }

  const std::string& name() const noexcept override { return host_.name_; }

 private:
  UsbDeviceHost& host_;
};

UsbDeviceHost::UsbDeviceHost(UsbControlDevice& device, std::string name) : device_(device), name_(std::move(name)) {}

std::unique_ptr<firmware_iface::UsbControlTransport> UsbDeviceHost::connect() { return std::make_unique<Connection>(*this); }

void UsbDeviceHost::set_plugged(bool plugged) {
  std::lock_guard lock(mutex_);
  plugged_ = plugged;
}

std::uint64_t UsbDeviceHost::transfers() const {
  std::lock_guard lock(mutex_);
  return transfers_;
}

}  // namespace avar::sim
