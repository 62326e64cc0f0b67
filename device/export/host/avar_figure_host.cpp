// The Linux side of an exported figure (avar export --target host): the same figure and shows as
// on a microcontroller, played by the device engine in a plain program on a Raspberry Pi or any
// Linux machine with PCA9685 boards on an I2C bus (/dev/i2c-N through i2c-dev). Commands come
// on standard input ('1'..'9' and Enter plays a show, 's' stops, 'q' eases to rest and quits);
// Ctrl-C and SIGTERM ease to rest and quit. --trace writes every I2C transaction to standard
// output instead of a bus, on simulated time, for a look before the servos are wired: it plays
// until the figure is at rest (or for --seconds).
//
// Safety, as on a board: the channels' limits apply every tick, servos glide from rest at start,
// stop and quit ease to rest (the servos then hold their rest pulses), a board that stops
// answering releases every output and the program exits with status 3.
#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>

#include "avar/device/figure.hpp"
#include "avar_shows.h"

namespace {

using namespace avar::device;

FigureStorage<AVAR_CHANNEL_COUNT, AVAR_BOARD_COUNT> storage;
Figure& figure = storage.figure;
volatile std::sig_atomic_t quit_asked = 0;

void on_signal(int) { quit_asked = 1; }

bool bus_write(void* context, uint8_t address, const uint8_t* bytes, uint8_t length) {
  const int fd = *static_cast<int*>(context);
  i2c_msg message{};
  message.addr = address;
  message.len = length;
  message.buf = const_cast<uint8_t*>(bytes);  // the kernel only reads a write's buffer
  i2c_rdwr_ioctl_data transfer{&message, 1};
  return ioctl(fd, I2C_RDWR, &transfer) >= 0;
}

bool trace_write(void*, uint8_t address, const uint8_t* bytes, uint8_t length) {
  std::printf("i2c 0x%02x:", address);
  for (uint8_t i = 0; i < length; ++i) std::printf(" %02x", bytes[i]);
  std::printf("\n");
  return true;
}

void sleep_us(void*, uint16_t us) {
  const timespec wait = {0, static_cast<long>(us) * 1000};
  nanosleep(&wait, nullptr);
}

void trace_wait(void*, uint16_t us) { std::printf("wait %u us\n", us); }

int usage(const char* program, int status) {
  std::fprintf(status == 0 ? stdout : stderr,
               "usage: %s [--bus /dev/i2c-N] [--play SHOW] [--trace] [--seconds S]\n"
               "Plays the exported figure's shows on PCA9685 boards on an I2C bus (default /dev/i2c-1).\n"
               "  --play SHOW   start show SHOW (1..%d) at once\n"
               "  --trace       print the I2C transactions instead of writing a bus, on simulated time,\n"
               "                until the figure rests (or for --seconds)\n"
               "  --seconds S   quit after S seconds (easing to rest first)\n"
               "On standard input: 1..%d and Enter plays a show, s stops, q eases to rest and quits.\n",
               program, AVAR_SHOW_COUNT, AVAR_SHOW_COUNT);
  return status;
}

/// The commands typed since the last tick (standard input, non-blocking); false at 'q' or its end.
bool read_commands() {
  char buffer[64];
  const ssize_t n = read(STDIN_FILENO, buffer, sizeof buffer);
  if (n == 0) return true;  // end of input: keep playing until a signal or --seconds
  for (ssize_t i = 0; i < n; ++i) {
    if (buffer[i] == 'q') return false;
    figure_command(figure, static_cast<uint8_t>(buffer[i]));
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::string bus = "/dev/i2c-1";
  int play = AVAR_BOOT_SHOW + 1;  // 1-based; 0: none
  bool trace = false;
  double seconds = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--help" || a == "-h") return usage(argv[0], 0);
    if (a == "--trace") trace = true;
    else if (a == "--bus" && has_value) bus = argv[++i];
    else if (a == "--play" && has_value) play = std::atoi(argv[++i]);
    else if (a == "--seconds" && has_value) seconds = std::atof(argv[++i]);
    else return usage(argv[0], 2);
  }
  if (play < 0 || play > AVAR_SHOW_COUNT) {
    std::fprintf(stderr, "--play: found %d; expected a show 1 to %d\n", play, AVAR_SHOW_COUNT);
    return 2;
  }
  int fd = -1;
  if (!trace) {
    fd = open(bus.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) {
      std::fprintf(stderr, "cannot open %s: %s (is i2c-dev loaded, and may this user use it?)\n", bus.c_str(),
                   std::strerror(errno));
      return 2;
    }
  }
  const FigureIo io = trace ? FigureIo{trace_write, trace_wait, nullptr, nullptr} : FigureIo{bus_write, sleep_us, nullptr, &fd};
  if (storage.open(avar_shows::kFigure, sizeof avar_shows::kFigure, avar_shows::kShows, AVAR_SHOW_COUNT) != kFigureOk) {
    std::fprintf(stderr, "the exported figure or a show does not check: export again with this avar\n");
    return 2;
  }
  if (figure_begin(figure, io) != kFigureOk) {
    std::fprintf(stderr, "a PCA9685 board does not answer on %s: every output released\n", bus.c_str());
    return 3;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  fcntl(STDIN_FILENO, F_SETFL, fcntl(STDIN_FILENO, F_GETFL) | O_NONBLOCK);
  if (play > 0) player_start(figure.player, static_cast<uint8_t>(play - 1));

  const long tick_ns = 1000000000L / AVAR_RATE_HZ;
  const long long last_tick = seconds > 0 ? static_cast<long long>(seconds * AVAR_RATE_HZ) : -1;
  timespec next;
  clock_gettime(CLOCK_MONOTONIC, &next);
  bool quitting = false;
  for (long long tick = 0;; ++tick) {
    if (!quitting && (quit_asked || (last_tick >= 0 && tick >= last_tick) || (!trace && !read_commands()))) {
      quitting = true;  // ease to rest, then leave the servos holding it
      player_stop(figure.player);
    }
#if AVAR_IDLE_SHOW >= 0
    if (!quitting && figure.player.mode == kPlayerResting) player_start(figure.player, AVAR_IDLE_SHOW);
#endif
    figure_tick(figure, io);
    if (figure.io_fault) {
      std::fprintf(stderr, "a PCA9685 board stopped answering: every output released\n");
      return 3;
    }
    if (figure.player.mode == kPlayerResting && (quitting || (trace && last_tick < 0))) break;
    if (trace) continue;
    next.tv_nsec += tick_ns;
    if (next.tv_nsec >= 1000000000L) {
      next.tv_nsec -= 1000000000L;
      ++next.tv_sec;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
  }
  if (fd >= 0) close(fd);
  return 0;
}
