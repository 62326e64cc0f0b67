#pragma once
// Fault injection between a USB host and a simulated device driven by control transfers: wraps
// any UsbControlDevice and, by a seeded FaultPlan, loses transfers, answers them late or short,
// makes the device stop answering, or makes it answer noise (FaultPlan::garbage: every answer's
// bytes random, in a transfer that otherwise succeeds). A lost or late transfer fails as the host
// controller reports it, with Status::timeout (beyond UsbControlDevice's ok / bad_data). USB's
// own CRC and retries keep corrupted, duplicated or reordered packets from a control transfer,
// so the plan's corrupt_reply, duplicate_reply and reorder_reply do not apply and are ignored.
// Not thread-safe, like every UsbControlDevice (its UsbDeviceHost serialises calls).

#include <random>

#include "avar/sim/faulty_device.hpp"
#include "avar/sim/usb_control_device.hpp"

namespace avar::sim {

class FaultyUsbDevice final : public UsbControlDevice {
 public:
  /// inner is borrowed and must outlive this. host_timeout_s: how long the host waits for a
  /// transfer; a reply delayed longer (FaultPlan::delay_reply_s) is a timeout.
  FaultyUsbDevice(UsbControlDevice& inner, FaultPlan plan, double host_timeout_s);

  void set_plan(const FaultPlan& plan);
  /// commands_dropped: transfers lost before the device saw them; replies_dropped: answers lost
  /// (or too late, or silenced); replies_truncated: answers cut short; replies_garbled and
  /// garbage_bytes: answers replaced by noise.
  const FaultCounts& counts() const { return counts_; }

  Status control(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* transferred) override;
  void advance(double dt_s) override { inner_.advance(dt_s); }

 private:
  bool chance(double p);

  UsbControlDevice& inner_;
  FaultPlan plan_;
  double host_timeout_s_;
  std::mt19937_64 random_;
  FaultCounts counts_;
};

}  // namespace avar::sim
