#include "avar/sim/faulty_usb_device.hpp"

namespace avar::sim {

FaultyUsbDevice::FaultyUsbDevice(UsbControlDevice& inner, FaultPlan plan, double host_timeout_s)
    : inner_(inner), plan_(plan), host_timeout_s_(host_timeout_s), random_(plan.seed) {}

void FaultyUsbDevice::set_plan(const FaultPlan& plan) {
  plan_ = plan;
  random_.seed(plan.seed);
}

bool FaultyUsbDevice::chance(double p) {
  if (p <= 0) return false;
  return std::uniform_real_distribution<double>(0.0, 1.0)(random_) < p;
}

Status FaultyUsbDevice::control(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* transferred) {
  *transferred = 0;
  if (chance(plan_.drop_command)) {
    ++counts_.commands_dropped;
    return Status::timeout;
  }
  const Status s = inner_.control(setup, data, transferred);
  if (plan_.silent) {
    ++counts_.replies_silenced;
    *transferred = 0;
    return Status::timeout;
  }
  if (plan_.delay_reply_s > host_timeout_s_ || chance(plan_.drop_reply)) {
    ++counts_.replies_dropped;
    *transferred = 0;
    return Status::timeout;
  }
  if (s == Status::ok && setup.device_to_host() && plan_.garbage) {
    for (std::size_t k = 0; k < *transferred; ++k)
      data[k] = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(random_));
    ++counts_.replies_garbled;
    counts_.garbage_bytes += *transferred;
  }
  if (s == Status::ok && setup.device_to_host() && *transferred > 1 && chance(plan_.truncate_reply)) {
    *transferred = std::uniform_int_distribution<std::size_t>(1, *transferred - 1)(random_);
    ++counts_.replies_truncated;
  }
  return s;
}

}  // namespace avar::sim
