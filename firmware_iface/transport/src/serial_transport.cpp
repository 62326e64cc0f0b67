#include "avar/firmware_iface/serial_transport.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <libserial/SerialPort.h>
#include <utility>

#include "avar/core/input_error.hpp"
#include "avar/core/monotonic_clock.hpp"
#include "avar/core/serial_rates.hpp"

namespace avar::firmware_iface {
namespace {

constexpr std::array<std::pair<int, LibSerial::BaudRate>, 23> kBaudRates{{
    {1200, LibSerial::BaudRate::BAUD_1200},       {2400, LibSerial::BaudRate::BAUD_2400},
    {4800, LibSerial::BaudRate::BAUD_4800},       {9600, LibSerial::BaudRate::BAUD_9600},
    {19200, LibSerial::BaudRate::BAUD_19200},     {38400, LibSerial::BaudRate::BAUD_38400},
    {57600, LibSerial::BaudRate::BAUD_57600},     {115200, LibSerial::BaudRate::BAUD_115200},
    {230400, LibSerial::BaudRate::BAUD_230400},   {460800, LibSerial::BaudRate::BAUD_460800},
    {500000, LibSerial::BaudRate::BAUD_500000},   {576000, LibSerial::BaudRate::BAUD_576000},
    {921600, LibSerial::BaudRate::BAUD_921600},   {1000000, LibSerial::BaudRate::BAUD_1000000},
    {1152000, LibSerial::BaudRate::BAUD_1152000}, {1500000, LibSerial::BaudRate::BAUD_1500000},
    {2000000, LibSerial::BaudRate::BAUD_2000000}, {2500000, LibSerial::BaudRate::BAUD_2500000},
    {3000000, LibSerial::BaudRate::BAUD_3000000}, {3500000, LibSerial::BaudRate::BAUD_3500000},
    {4000000, LibSerial::BaudRate::BAUD_4000000}, {300, LibSerial::BaudRate::BAUD_300},
    {600, LibSerial::BaudRate::BAUD_600},
}};

constexpr bool maps_exactly_the_standard_rates() {
  if (kBaudRates.size() != kStandardBauds.size()) return false;
  for (const auto& [rate, code] : kBaudRates)
    if (!is_standard_baud(rate)) return false;
  for (const int rate : kStandardBauds) {
    bool mapped = false;
    for (const auto& entry : kBaudRates) mapped = mapped || entry.first == rate;
    if (!mapped) return false;
  }
  return true;
}
static_assert(maps_exactly_the_standard_rates(), "every standard baud rate needs its libserial code, and only those");

[[noreturn]] void port_error(const std::string& path, const std::string& problem) { throw InputError({path, 0, 0}, problem); }

}  // namespace

bool SerialTransport::is_supported_baud(int baud) noexcept { return is_standard_baud(baud); }

SerialTransport::SerialTransport(const std::string& path, int baud)
    : path_(path), baud_(baud), port_(std::make_unique<LibSerial::SerialPort>()) {
  if (!is_supported_baud(baud))
    port_error(path, "baud rate " + std::to_string(baud) + " is not a standard serial rate (e.g. 9600, 57600, 115200, 1000000)");
  write_buffer_.reserve(max_chunk);
  read_buffer_.reserve(max_chunk);
  open_port();
}

void SerialTransport::open_port() {
  LibSerial::BaudRate code = LibSerial::BaudRate::BAUD_INVALID;
  for (const auto& [rate, c] : kBaudRates)
    if (rate == baud_) code = c;
  const std::string& path = path_;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    port_error(path, std::string("cannot open serial port: ") + std::strerror(errno) +
                         "; expected a serial device such as /dev/ttyACM0 (is it plugged in?)");
  if (!S_ISCHR(st.st_mode)) port_error(path, "not a serial device (expected a character device such as /dev/ttyACM0)");

  try {
    port_->Open(path);
  } catch (const std::exception& e) {
    port_error(path, std::string("cannot open serial port: ") + e.what() + " (" + std::strerror(errno) +
                         "); check permissions (the dialout group) and that no other program has it open");
  }
  // An advisory lock makes a second avar (or any flock-aware program) fail fast instead of
  // interleaving bytes with us on one device.
  if (::flock(port_->GetFileDescriptor(), LOCK_EX | LOCK_NB) != 0) {
    port_->Close();
    port_error(path, "serial port is busy: another program has it open");
  }
  try {
    port_->SetBaudRate(code);
    port_->SetCharacterSize(LibSerial::CharacterSize::CHAR_SIZE_8);
    port_->SetParity(LibSerial::Parity::PARITY_NONE);
    port_->SetStopBits(LibSerial::StopBits::STOP_BITS_1);
    port_->SetFlowControl(LibSerial::FlowControl::FLOW_CONTROL_NONE);
    port_->FlushIOBuffers();
  } catch (const std::exception& e) {
    port_->Close();
    port_error(path, std::string("cannot configure serial port: ") + e.what());
  }
}

void SerialTransport::close_port() noexcept {
  int fd = -1;
  try {
    if (!port_->IsOpen()) return;
    fd = port_->GetFileDescriptor();
    port_->Close();
    return;
  } catch (...) {
    // libserial restores the old terminal settings before closing, which fails once the device
    // has vanished (EIO), leaving an object that believes it is open and whose destructor would
    // throw. Put a live terminal (a fresh pseudo-terminal) under the same descriptor number so
    // that the second Close succeeds and closes it.
  }
  int master = -1, slave = -1;
  if (fd >= 0 && ::openpty(&master, &slave, nullptr, nullptr, nullptr) == 0) {
    ::dup2(slave, fd);
    ::close(slave);
    try {
      port_->Close();
    } catch (...) {
      // Nothing more can be done; the descriptor is closed below at worst.
    }
    ::close(master);
  }
}

SerialTransport::~SerialTransport() { close_port(); }

Status SerialTransport::reopen() noexcept {
  close_port();
  try {
    port_ = std::make_unique<LibSerial::SerialPort>();
    open_port();
    return Status::ok;
  } catch (...) {
    return Status::io_error;
  }
}

Status SerialTransport::write(std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.size() > max_chunk) return Status::out_of_range;
  try {
    write_buffer_.assign(bytes.begin(), bytes.end());
    port_->Write(write_buffer_);
    bytes_written_.fetch_add(bytes.size(), std::memory_order_relaxed);
    return Status::ok;
  } catch (...) {
    return Status::io_error;
  }
}

Status SerialTransport::read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds timeout) noexcept {
  if (out.size() > max_chunk) return Status::out_of_range;
  if (out.empty()) return Status::ok;
  try {
    read_buffer_.clear();
    port_->Read(read_buffer_, out.size(), static_cast<std::size_t>(std::max<long>(1, static_cast<long>(timeout.count()))));
    if (read_buffer_.size() != out.size()) return Status::timeout;
    std::copy(read_buffer_.begin(), read_buffer_.end(), out.begin());
    return Status::ok;
  } catch (const LibSerial::ReadTimeout&) {
    return Status::timeout;
  } catch (...) {
    return Status::io_error;
  }
}

Status SerialTransport::read_some(std::span<std::uint8_t> out, std::chrono::milliseconds timeout, std::size_t* got) noexcept {
  *got = 0;
  if (out.empty()) return Status::ok;
  int fd = -1;
  try {
    if (!port_->IsOpen()) return Status::io_error;
    fd = port_->GetFileDescriptor();
  } catch (...) {
    return Status::io_error;
  }
  // Straight on the descriptor: poll for the first byte, then one read of what is there (no
  // buffer of libserial's in between, so nothing is allocated).
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::max<std::int64_t>(0, left.count())));
    if (ready < 0) {
      if (errno == EINTR) continue;
      return Status::io_error;
    }
    if (ready == 0) return Status::timeout;
    if (p.revents & (POLLERR | POLLNVAL)) return Status::io_error;
    const ssize_t n = ::read(fd, out.data(), out.size());
    if (n > 0) {
      *got = static_cast<std::size_t>(n);
      return Status::ok;
    }
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    return Status::io_error;  // end of file or EIO: the device vanished
  }
}

std::chrono::nanoseconds SerialTransport::now() const noexcept { return std::chrono::nanoseconds(monotonic_ns()); }

void SerialTransport::discard_input() noexcept {
  try {
    port_->FlushInputBuffer();
  } catch (...) {
    // A port that cannot be flushed will report its failure on the next read or write.
  }
}

}  // namespace avar::firmware_iface
