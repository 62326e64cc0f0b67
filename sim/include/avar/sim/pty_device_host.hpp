#pragma once
// Serves a simulated device on the master side of a pseudo-terminal, in a background thread,
// so that a real serial driver can open the slave side (/dev/pts/N) exactly as it opens
// /dev/ttyACM0. The pty is raw: no echo, no line editing, no CR/LF translation.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "avar/sim/byte_device.hpp"

namespace avar::sim {

class PtyDeviceHost {
 public:
  /// stepped: the device's time moves only when the owner calls advance() through
  /// with_device() (deterministic runs). wall: the host thread advances it every 10 ms of
  /// monotonic time (a stand-alone simulator).
  enum class Clock { stepped, wall };

  /// Opens the pseudo-terminal and starts serving. Throws std::runtime_error when no pty can
  /// be had. The device is borrowed and must outlive the host.
  PtyDeviceHost(ByteDevice& device, Clock clock);
  ~PtyDeviceHost();
  PtyDeviceHost(const PtyDeviceHost&) = delete;
  PtyDeviceHost& operator=(const PtyDeviceHost&) = delete;

  /// The path a serial driver opens.
  const std::string& slave_path() const { return slave_path_; }

  /// Blocks until the device has taken in `total_bytes` bytes since the start, or the timeout
  /// passes (returns false). The sync point of stepped simulated time.
  bool wait_consumed(std::uint64_t total_bytes, std::chrono::milliseconds timeout);

  /// Runs f(device) while the host thread is kept away from the device.
  template <class F>
  auto with_device(F&& f) {
    std::lock_guard lock(mutex_);
    return f(device_);
  }

 private:
  void serve();

  ByteDevice& device_;
  Clock clock_;
  int master_ = -1;
  int slave_ = -1;      ///< kept open so the master never sees a hang-up between clients
  int wake_[2] = {-1, -1};
  std::string slave_path_;
  std::mutex mutex_;
  std::condition_variable consumed_cv_;
  std::thread thread_;
};

}  // namespace avar::sim
