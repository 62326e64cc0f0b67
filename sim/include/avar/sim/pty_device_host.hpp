#pragma once
// Serves a simulated device on the master side of a pseudo-terminal, in a background thread,
// so that a real serial driver opens the slave side (/dev/pts/N) exactly as it opens
// /dev/ttyACM0. The pty is raw: no echo, no line editing, no output processing.
//
// The host keeps its own descriptor of the slave open for its whole life, so clients may open
// and close the slave freely: the master never sees a hang-up (Linux reports EIO/POLLHUP on the
// master while no slave descriptor is open) and the raw settings persist between clients.
// Replies are sent as the device queues them: after each burst of client bytes, after each
// wall-clock step and after with_device(), so a device may speak unprompted (a simulated CAN
// bus's cyclic frames). Replies that nobody reads stay queued on the slave until a client reads or flushes them
// (avar's SerialTransport flushes on open); when that queue is full further replies are
// dropped, as bytes sent down a wire nobody listens to are lost.
//
// Thread safety: every member may be called from any thread; the device is only touched under
// the host's mutex (by the host thread, with_device() and wait_consumed()).

#include <atomic>
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
  /// with_device() (deterministic runs). wall: the host thread also advances it by the elapsed
  /// monotonic time every 10 ms and sends what the device says meanwhile (a stand-alone
  /// simulator such as `avar sim maestro --pty`).
  enum class Clock { stepped, wall };

  /// Opens the pseudo-terminal and starts serving. Throws std::runtime_error when no pty can
  /// be had. The device is borrowed and must outlive the host.
  PtyDeviceHost(ByteDevice& device, Clock clock);
  /// Stops the host thread, then closes both sides of the pty (a client still holding the
  /// slave open then reads end of file / EIO).
  ~PtyDeviceHost();
  PtyDeviceHost(const PtyDeviceHost&) = delete;
  PtyDeviceHost& operator=(const PtyDeviceHost&) = delete;

  /// The path a serial driver opens, e.g. /dev/pts/3.
  const std::string& slave_path() const { return slave_path_; }

  /// Blocks until the device has taken in `total_bytes` bytes since it was made (its
  /// bytes_received()), or the timeout passes (returns false). The sync point of stepped
  /// simulated time: after a client wrote N bytes in total, wait_consumed(N) then advance().
  bool wait_consumed(std::uint64_t total_bytes, std::chrono::milliseconds timeout);

  /// Blocks until pred(ByteDevice&) holds or the timeout passes (returns false). pred runs
  /// under the lock, now and after every change: each burst of bytes the device takes, each
  /// wall-clock step, each with_device() call. pred must not call back into this host.
  template <class Pred>
  bool wait_until(Pred&& pred, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return changed_cv_.wait_for(lock, timeout, [&] { return pred(device_); });
  }

  /// Runs f(ByteDevice&) while the host thread is kept away from the device; returns what f
  /// returns, sends the client whatever the device queued meanwhile (frames a simulated bus
  /// produced as its time moved), then wakes wait_until(). f must not call back into this host.
  template <class F>
  auto with_device(F&& f) {
    struct NotifyAfterUnlock {
      std::condition_variable& cv;
      ~NotifyAfterUnlock() { cv.notify_all(); }
    } notify{changed_cv_};
    std::lock_guard lock(mutex_);
    struct SendRepliesAfter {
      PtyDeviceHost& host;
      ~SendRepliesAfter() { host.send_replies_locked(); }
    } send{*this};
    return f(device_);
  }

  /// Switches from the wall clock to stepped time (a simulated drive that needed its own time
  /// to come up, now handed to the loop's stepped clock). Switching to wall takes effect within
  /// the next wake-up only. Any thread.
  void set_clock(Clock clock) { clock_.store(clock, std::memory_order_release); }

  /// How many times the host thread has woken from poll(): once per burst of bytes from the
  /// client, plus once per 10 ms in wall mode. An idle stepped host does not wake, whether or
  /// not a client holds the slave open (diagnostics; the proof that it does not spin).
  std::uint64_t serve_wakeups() const { return wakeups_.load(std::memory_order_relaxed); }

 private:
  void serve();
  /// Writes every reply the device has queued to the master; the caller holds mutex_.
  void send_replies_locked() noexcept;
  void close_all() noexcept;

  ByteDevice& device_;
  std::atomic<Clock> clock_;
  int master_ = -1;
  int slave_ = -1;  ///< held open so the master never sees a hang-up between clients
  int wake_[2] = {-1, -1};
  std::string slave_path_;
  std::mutex mutex_;
  std::condition_variable changed_cv_;
  std::atomic<std::uint64_t> wakeups_{0};
  std::thread thread_;
};

}  // namespace avar::sim
