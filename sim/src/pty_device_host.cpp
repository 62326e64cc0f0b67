#include "avar/sim/pty_device_host.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace avar::sim {
namespace {

constexpr auto kWallStep = std::chrono::milliseconds(10);

[[noreturn]] void fail(const char* what) {
  throw std::runtime_error(std::string("pseudo-terminal device host: ") + what + ": " + std::strerror(errno));
}

/// Writes what the master takes without waiting; the rest is dropped (see the header).
void write_or_drop(int fd, const std::uint8_t* data, std::size_t size) noexcept {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

}  // namespace

PtyDeviceHost::PtyDeviceHost(ByteDevice& device, Clock clock) : device_(device), clock_(clock) {
  if (::openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) fail("cannot open a pseudo-terminal");
  try {
    std::array<char, 128> name{};
    if (::ptsname_r(master_, name.data(), name.size()) != 0) fail("cannot name the pseudo-terminal");
    slave_path_ = name.data();
    termios raw{};
    if (::tcgetattr(slave_, &raw) != 0) fail("cannot read the terminal settings");
    ::cfmakeraw(&raw);  // no echo, no canonical mode, no signals, no CR/LF mapping, no OPOST
    raw.c_cc[VMIN] = 1;
    raw.c_cc[VTIME] = 0;
    if (::tcsetattr(slave_, TCSANOW, &raw) != 0) fail("cannot make the terminal raw");
    // Child processes (an `avar` run under test) must not inherit the pty's ends.
    if (::fcntl(master_, F_SETFD, FD_CLOEXEC) != 0 || ::fcntl(slave_, F_SETFD, FD_CLOEXEC) != 0) fail("cannot set close-on-exec");
    if (::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK) != 0) fail("cannot make the master non-blocking");
    if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) fail("cannot create the wake-up pipe");
    thread_ = std::thread([this] { serve(); });
  } catch (...) {
    close_all();
    throw;
  }
}

PtyDeviceHost::~PtyDeviceHost() {
  const std::uint8_t stop = 1;
  while (::write(wake_[1], &stop, 1) < 0 && errno == EINTR) {
  }
  thread_.join();
  close_all();
}

void PtyDeviceHost::close_all() noexcept {
  for (int* fd : {&wake_[0], &wake_[1], &slave_, &master_}) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }
}

bool PtyDeviceHost::wait_consumed(std::uint64_t total_bytes, std::chrono::milliseconds timeout) {
  return wait_until([&](const ByteDevice& d) { return d.bytes_received() >= total_bytes; }, timeout);
}

void PtyDeviceHost::send_replies_locked() noexcept {
  std::array<std::uint8_t, 4096> out{};
  try {
    for (std::size_t n = device_.take_replies(out); n > 0; n = device_.take_replies(out)) write_or_drop(master_, out.data(), n);
  } catch (...) {
    // A device that fails to hand over its replies answers nothing, as on a dead wire.
  }
}

void PtyDeviceHost::serve() {
  std::array<std::uint8_t, 4096> in{};
  using clock = std::chrono::steady_clock;
  auto last_advance = clock::now();
  for (;;) {
    int timeout_ms = -1;
    const Clock clock_now = clock_.load(std::memory_order_acquire);
    if (clock_now == Clock::wall) {
      const auto left = last_advance + kWallStep - clock::now();
      timeout_ms = static_cast<int>(std::max<std::int64_t>(0, std::chrono::ceil<std::chrono::milliseconds>(left).count()));
    }
    // The host's own slave descriptor stays open, so the master never reports POLLHUP and
    // this poll blocks while no client writes, whether or not a client has the slave open.
    std::array<pollfd, 2> fds{pollfd{master_, POLLIN, 0}, pollfd{wake_[0], POLLIN, 0}};
    const int ready = ::poll(fds.data(), fds.size(), timeout_ms);
    if (ready < 0 && errno != EINTR) return;
    wakeups_.fetch_add(1, std::memory_order_relaxed);
    if (ready > 0 && (fds[1].revents & POLLIN)) return;

    if (ready > 0 && (fds[0].revents & POLLIN)) {
      const ssize_t n = ::read(master_, in.data(), in.size());
      if (n > 0) {
        {
          // Replies are written under the lock, so that those sent after with_device() never
          // overtake these (the master is non-blocking: writing does not wait).
          std::lock_guard lock(mutex_);
          device_.receive(std::span(in.data(), static_cast<std::size_t>(n)));
          send_replies_locked();
        }
        changed_cv_.notify_all();
      }
    }
    if (clock_now == Clock::wall) {
      const auto now = clock::now();
      if (now - last_advance >= kWallStep) {
        {
          std::lock_guard lock(mutex_);
          device_.advance(std::chrono::duration<double>(now - last_advance).count());
          send_replies_locked();  // what the device says as time passes (a drive's heartbeat)
        }
        last_advance = now;
        changed_cv_.notify_all();
      }
    }
  }
}

}  // namespace avar::sim
