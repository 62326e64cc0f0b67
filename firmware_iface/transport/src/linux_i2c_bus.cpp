#include "avar/firmware_iface/linux_i2c_bus.hpp"

#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace avar::firmware_iface {
namespace {

class LinuxI2cBus final : public I2cBus {
 public:
  explicit LinuxI2cBus(const std::string& path) : description_("I2C bus " + path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0)
      throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno) +
                               " (is i2c-dev loaded, and may this user use it?)");
    unsigned long functions = 0;
    if (::ioctl(fd_, I2C_FUNCS, &functions) < 0 || !(functions & I2C_FUNC_I2C)) {
      ::close(fd_);
      throw std::runtime_error(path + " is not an I2C adapter that takes plain transactions (I2C_FUNC_I2C)");
    }
  }
  ~LinuxI2cBus() override { ::close(fd_); }
  LinuxI2cBus(const LinuxI2cBus&) = delete;
  LinuxI2cBus& operator=(const LinuxI2cBus&) = delete;

  Status write(std::uint8_t address, std::span<const std::uint8_t> bytes) noexcept override {
    i2c_msg message{};
    message.addr = address;
    message.flags = 0;
    message.len = static_cast<__u16>(bytes.size());
    message.buf = const_cast<__u8*>(bytes.data());  // the kernel only reads a write's buffer
    i2c_rdwr_ioctl_data transfer{&message, 1};
    return ::ioctl(fd_, I2C_RDWR, &transfer) < 0 ? Status::io_error : Status::ok;
  }
  void settle(std::uint32_t us) override { std::this_thread::sleep_for(std::chrono::microseconds(us)); }
  const std::string& describe() const noexcept override { return description_; }

 private:
  int fd_ = -1;
  std::string description_;
};

}  // namespace

std::unique_ptr<I2cBus> open_i2c_bus(const std::string& path) { return std::make_unique<LinuxI2cBus>(path); }

}  // namespace avar::firmware_iface
