#include "avar/firmware_iface/sysfs_pwm_chip.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

namespace avar::firmware_iface {
namespace {

bool all_digits(const std::string& s) { return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos; }

/// One whole write of a decimal number at the file's start (sysfs attributes take one value per
/// write). Real-time safe: no allocation.
bool write_number(int fd, std::uint64_t value) noexcept {
  char text[24];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
  if (ec != std::errc()) return false;
  const auto length = static_cast<std::size_t>(end - text);
  return ::pwrite(fd, text, length, 0) == static_cast<ssize_t>(length);
}

/// Load-time writes of one attribute; throws naming the file and the system's reason.
void write_attribute(const std::string& path, const std::string& value) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
  const ssize_t written = ::write(fd, value.data(), value.size());
  const int error = errno;
  ::close(fd);
  if (written != static_cast<ssize_t>(value.size()))
    throw std::runtime_error("writing " + value + " to " + path + " failed: " + std::strerror(error));
}

class SysfsPwmChip final : public PwmChip {
 public:
  SysfsPwmChip(std::string directory, unsigned outputs)
      : directory_(std::move(directory)), description_("PWM chip " + directory_), outputs_(outputs) {}
  SysfsPwmChip(const SysfsPwmChip&) = delete;
  SysfsPwmChip& operator=(const SysfsPwmChip&) = delete;
  ~SysfsPwmChip() override {
    for (Output& o : outputs_) {
      if (o.enable >= 0) write_number(o.enable, 0);
      if (o.enable >= 0) ::close(o.enable);
      if (o.duty >= 0) ::close(o.duty);
    }
  }

  void open_output(unsigned output, std::uint32_t period_ns) override {
    if (output >= outputs_.size())
      throw std::runtime_error(description_ + " has outputs 0 to " + std::to_string(outputs_.size() - 1) + ", not " +
                               std::to_string(output));
    Output& o = outputs_[output];
    if (o.duty >= 0) throw std::runtime_error(description_ + ": output " + std::to_string(output) + " is opened twice");
    const std::string dir = directory_ + "/pwm" + std::to_string(output);
    if (::access(dir.c_str(), F_OK) != 0) write_attribute(directory_ + "/export", std::to_string(output));
    // A newly exported output's files belong to root until udev gives them to the gpio group.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (::access((dir + "/duty_cycle").c_str(), W_OK) != 0) {
      if (std::chrono::steady_clock::now() > deadline)
        throw std::runtime_error("output " + std::to_string(output) + " of " + description_ + " did not appear writable at " +
                                 dir + "/duty_cycle (is this user in the group that owns it?)");
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    // Off, no pulse, then the period (a period below the present pulse is refused), upright.
    write_attribute(dir + "/enable", "0");
    write_attribute(dir + "/duty_cycle", "0");
    write_attribute(dir + "/period", std::to_string(period_ns));
    if (::access((dir + "/polarity").c_str(), W_OK) == 0) write_attribute(dir + "/polarity", "normal");
    o.duty = ::open((dir + "/duty_cycle").c_str(), O_WRONLY | O_CLOEXEC);
    o.enable = ::open((dir + "/enable").c_str(), O_WRONLY | O_CLOEXEC);
    if (o.duty < 0 || o.enable < 0)
      throw std::runtime_error("cannot open output " + std::to_string(output) + " of " + description_ + ": " +
                               std::strerror(errno));
    o.period_ns = period_ns;
  }

  Status set_pulse(unsigned output, std::uint32_t pulse_ns) noexcept override {
    if (output >= outputs_.size() || outputs_[output].duty < 0) return Status::out_of_range;
    Output& o = outputs_[output];
    if (pulse_ns > o.period_ns) return Status::out_of_range;
    if (!write_number(o.duty, pulse_ns)) return Status::io_error;
    if (!o.on) {
      if (!write_number(o.enable, 1)) return Status::io_error;
      o.on = true;
    }
    return Status::ok;
  }

  Status switch_off(unsigned output) noexcept override {
    if (output >= outputs_.size() || outputs_[output].enable < 0) return Status::out_of_range;
    Output& o = outputs_[output];
    if (!write_number(o.enable, 0)) return Status::io_error;
    o.on = false;
    return Status::ok;
  }

  const std::string& describe() const noexcept override { return description_; }

 private:
  struct Output {
    int duty = -1, enable = -1;  ///< the kept-open attribute files
    std::uint32_t period_ns = 0;
    bool on = false;
  };
  std::string directory_;
  std::string description_;
  std::vector<Output> outputs_;
};

}  // namespace

std::unique_ptr<PwmChip> open_pwm_chip(const std::string& port, const std::string& sysfs_root) {
  std::string directory = port;
  if (all_digits(port)) directory = sysfs_root + "/pwmchip" + port;
  else if (port.find('/') == std::string::npos) directory = sysfs_root + "/" + port;
  std::ifstream npwm(directory + "/npwm");
  unsigned outputs = 0;
  if (!(npwm >> outputs) || outputs == 0) {
    std::string why = "no PWM chip '" + port + "' (" + directory + "/npwm cannot be read";
    if (port.find('/') == std::string::npos) {
      bool any = false;
      for (int n = 0; n < 64 && !any; ++n) any = ::access((sysfs_root + "/pwmchip" + std::to_string(n)).c_str(), F_OK) == 0;
      if (::access(sysfs_root.c_str(), F_OK) != 0) why += "; this machine has none: " + sysfs_root + " is absent";
      else if (!any) why += "; this machine has none: " + sysfs_root + " lists no pwmchip";
    }
    throw std::runtime_error(why + ")");
  }
  return std::make_unique<SysfsPwmChip>(std::move(directory), outputs);
}

}  // namespace avar::firmware_iface
