// The GPIO seam over libgpiod's v1 API (Debian 12 ships 1.6): one gpiod_chip, its lines
// requested one by one with the consumer name "avar"; edges are read from the lines' event file
// descriptors with poll().
#include "avar/firmware_iface/libgpiod_chip.hpp"

#include <gpiod.h>
#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace avar::firmware_iface {
namespace {

constexpr const char* kConsumer = "avar";

int flags_of(bool active_low, GpioBias bias) {
  int flags = active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  switch (bias) {
    case GpioBias::as_is: break;
    case GpioBias::disabled: flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE; break;
    case GpioBias::pull_up: flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP; break;
    case GpioBias::pull_down: flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN; break;
  }
  return flags;
}

std::string chips_here() {
  const std::vector<std::string> names = gpio_chip_names();
  if (names.empty()) return "this machine has none: /dev/gpiochip* absent";
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return "chips here: " + list;
}

class LibgpiodChip final : public GpioChip {
 public:
  explicit LibgpiodChip(gpiod_chip* chip) : chip_(chip) {
    describe_ = std::string("GPIO chip '") + gpiod_chip_name(chip) + "' (" + gpiod_chip_label(chip) + ")";
  }
  ~LibgpiodChip() override {
    for (const Requested& r : lines_) gpiod_line_release(r.line);
    gpiod_chip_close(chip_);
  }
  LibgpiodChip(const LibgpiodChip&) = delete;
  LibgpiodChip& operator=(const LibgpiodChip&) = delete;

  const std::string& describe() const noexcept override { return describe_; }
  unsigned line_count() const noexcept override { return gpiod_chip_num_lines(chip_); }

  void request_input(const GpioInputRequest& request) override {
    gpiod_line* line = line_for(request.line);
    const int flags = flags_of(request.active_low, request.bias);
    const int rc = request.edge_events ? gpiod_line_request_both_edges_events_flags(line, kConsumer, flags)
                                       : gpiod_line_request_input_flags(line, kConsumer, flags);
    if (rc != 0) fail_request(request.line, "as an input");
    lines_.push_back({request.line, line, false, request.edge_events ? gpiod_line_event_get_fd(line) : -1});
  }

  void request_output(const GpioOutputRequest& request) override {
    gpiod_line* line = line_for(request.line);
    if (gpiod_line_request_output_flags(line, kConsumer, flags_of(request.active_low, GpioBias::as_is),
                                        request.initial ? 1 : 0) != 0)
      fail_request(request.line, "as an output");
    lines_.push_back({request.line, line, true, -1});
  }

  void release(unsigned line) noexcept override {
    const auto it = std::find_if(lines_.begin(), lines_.end(), [&](const Requested& r) { return r.offset == line; });
    if (it == lines_.end()) return;
    gpiod_line_release(it->line);
    lines_.erase(it);
  }

  Status get(unsigned line, bool& value) noexcept override {
    const Requested* r = find(line);
    if (!r) return Status::out_of_range;
    const int v = gpiod_line_get_value(r->line);
    if (v < 0) return Status::io_error;
    value = v != 0;
    return Status::ok;
  }

  Status set(unsigned line, bool value) noexcept override {
    const Requested* r = find(line);
    if (!r || !r->output) return Status::out_of_range;
    return gpiod_line_set_value(r->line, value ? 1 : 0) == 0 ? Status::ok : Status::io_error;
  }

  Status wait_edges(std::chrono::nanoseconds timeout, std::span<GpioEdge> out, std::size_t& count) noexcept override {
    count = 0;
    pollfd fds[GPIOD_LINE_BULK_MAX_LINES];
    unsigned offsets[GPIOD_LINE_BULK_MAX_LINES];
    nfds_t n = 0;
    for (const Requested& r : lines_)
      if (r.event_fd >= 0 && n < GPIOD_LINE_BULK_MAX_LINES) fds[n] = {r.event_fd, POLLIN | POLLPRI, 0}, offsets[n++] = r.offset;
    const timespec ts{static_cast<time_t>(timeout.count() / 1'000'000'000), static_cast<long>(timeout.count() % 1'000'000'000)};
    const int ready = ppoll(fds, n, &ts, nullptr);
    if (ready < 0) return errno == EINTR ? Status::ok : Status::io_error;
    for (nfds_t i = 0; i < n && count < out.size(); ++i) {
      if (fds[i].revents == 0) continue;
      if (fds[i].revents & (POLLERR | POLLNVAL)) return Status::io_error;
      gpiod_line_event event{};
      if (gpiod_line_event_read_fd(fds[i].fd, &event) != 0) return Status::io_error;
      out[count++] = {offsets[i], event.event_type == GPIOD_LINE_EVENT_RISING_EDGE,
                      static_cast<std::int64_t>(event.ts.tv_sec) * 1'000'000'000 + event.ts.tv_nsec};
    }
    return Status::ok;
  }

 private:
  struct Requested {
    unsigned offset;
    gpiod_line* line;
    bool output;
    int event_fd;
  };

  gpiod_line* line_for(unsigned offset) {
    const unsigned lines = gpiod_chip_num_lines(chip_);
    if (offset >= lines)
      throw std::runtime_error(describe_ + " has " + std::to_string(lines) + " lines (0 to " + std::to_string(lines - 1) +
                               "); line " + std::to_string(offset) + " does not exist");
    if (find(offset)) throw std::runtime_error(describe_ + ": line " + std::to_string(offset) + " is requested twice by avar");
    gpiod_line* line = gpiod_chip_get_line(chip_, offset);
    if (!line) throw std::runtime_error(describe_ + ": cannot get line " + std::to_string(offset) + ": " + std::strerror(errno));
    return line;
  }

  [[noreturn]] void fail_request(unsigned offset, const char* how) const {
    const int err = errno;
    throw std::runtime_error(describe_ + ": cannot request line " + std::to_string(offset) + " " + how + ": " +
                             std::strerror(err) + (err == EBUSY ? " (another program holds it)" : ""));
  }

  const Requested* find(unsigned offset) const noexcept {
    for (const Requested& r : lines_)
      if (r.offset == offset) return &r;
    return nullptr;
  }

  gpiod_chip* chip_;
  std::string describe_;
  std::vector<Requested> lines_;
};

}  // namespace

const char* to_string(GpioBias b) noexcept {
  switch (b) {
    case GpioBias::as_is: return "as_is";
    case GpioBias::disabled: return "disabled";
    case GpioBias::pull_up: return "pull_up";
    case GpioBias::pull_down: return "pull_down";
  }
  return "unknown";
}

std::vector<std::string> gpio_chip_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/dev", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("gpiochip", 0) == 0) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::unique_ptr<GpioChip> open_gpio_chip(const std::string& name) {
  gpiod_chip* chip = gpiod_chip_open_lookup(name.c_str());
  if (!chip) {
    const int err = errno;
    if (err == EACCES || err == EPERM)
      throw std::runtime_error("cannot open GPIO chip '" + name + "': " + std::strerror(err) +
                               " (add the user to the gpio group, or check the permissions of /dev/" + name + ")");
    throw std::runtime_error("no GPIO chip '" + name + "' (" + chips_here() + ")");
  }
  return std::make_unique<LibgpiodChip>(chip);
}

}  // namespace avar::firmware_iface
