#include "avar/sim/pty_device_host.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace avar::sim {
namespace {

void write_all(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      pollfd p{fd, POLLOUT, 0};
      if (errno == EAGAIN && ::poll(&p, 1, 100) > 0) continue;
      return;  // nobody reads the slave side: the reply is lost, as on a real wire
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

}  // namespace

PtyDeviceHost::PtyDeviceHost(ByteDevice& device, Clock clock) : device_(device), clock_(clock) {
  termios raw{};
  cfmakeraw(&raw);
  std::array<char, 256> name{};
  if (::openpty(&master_, &slave_, name.data(), &raw, nullptr) != 0)
    throw std::runtime_error(std::string("cannot open a pseudo-terminal: ") + std::strerror(errno));
  slave_path_ = name.data();
  ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
  if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) {
    ::close(master_);
    ::close(slave_);
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  thread_ = std::thread([this] { serve(); });
}

PtyDeviceHost::~PtyDeviceHost() {
  const std::uint8_t stop = 1;
  (void)!::write(wake_[1], &stop, 1);
  thread_.join();
  ::close(wake_[0]);
  ::close(wake_[1]);
  ::close(slave_);
  ::close(master_);
}

bool PtyDeviceHost::wait_consumed(std::uint64_t total_bytes, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  return consumed_cv_.wait_for(lock, timeout, [&] { return device_.bytes_received() >= total_bytes; });
}

void PtyDeviceHost::serve() {
  std::array<std::uint8_t, 4096> in{};
  std::array<std::uint8_t, 4096> out{};
  auto last_advance = std::chrono::steady_clock::now();
  constexpr auto kWallStep = std::chrono::milliseconds(10);
  for (;;) {
    std::array<pollfd, 2> fds{pollfd{master_, POLLIN, 0}, pollfd{wake_[0], POLLIN, 0}};
    const int timeout_ms = clock_ == Clock::wall ? 10 : -1;
    if (::poll(fds.data(), fds.size(), timeout_ms) < 0 && errno != EINTR) return;
    if (fds[1].revents & POLLIN) return;

    if (fds[0].revents & POLLIN) {
      const ssize_t n = ::read(master_, in.data(), in.size());
      if (n > 0) {
        std::size_t reply = 0;
        {
          std::lock_guard lock(mutex_);
          device_.receive(std::span(in.data(), static_cast<std::size_t>(n)));
          reply = device_.take_replies(out);
        }
        consumed_cv_.notify_all();
        write_all(master_, out.data(), reply);
      }
    }
    if (clock_ == Clock::wall) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_advance >= kWallStep) {
        std::lock_guard lock(mutex_);
        device_.advance(std::chrono::duration<double>(now - last_advance).count());
        last_advance = now;
      }
    }
  }
}

}  // namespace avar::sim
