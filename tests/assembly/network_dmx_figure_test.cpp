// Network DMX figures end to end through the library: the example Art-Net and sACN rigs play
// their show against the simulated node on loopback; every tick the node's levels are the
// commanded values (to the DMX step), while bad datagrams of every kind sent to the node between
// ticks are counted and disturb neither the universe nor the show.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../support/stepped_figure_run.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/firmware_iface/artnet_dmx_codec.hpp"
#include "avar/firmware_iface/sacn_codec.hpp"

namespace avar {
namespace {

/// Sends junk to the node between ticks and checks the node's truth against the commands.
class NetworkDmxWatch final : public control::TickObserver {
 public:
  NetworkDmxWatch(const rig::Rig& rig, assembly::FigureLinks& figure, std::size_t link)
      : rig_(rig), figure_(figure), node_(*figure.simulated_node(link)) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    to_.sin_family = AF_INET;
    to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to_.sin_port = htons(node_.port());
    for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) channels_.push_back(a.channel.value);
  }
  ~NetworkDmxWatch() override { ::close(fd_); }
  NetworkDmxWatch(const NetworkDmxWatch&) = delete;
  NetworkDmxWatch& operator=(const NetworkDmxWatch&) = delete;

  void after_tick(std::uint64_t tick, double, double, double, control::Controller& c) override {
    std::vector<double> measured(rig_.channels.size(), 0);
    std::unique_ptr<bool[]> known(new bool[rig_.channels.size()]());
    figure_.measure(measured, std::span<bool>(known.get(), rig_.channels.size()));
    for (const std::size_t ch : channels_) {
      const rig::ChannelSpec& spec = rig_.channels[ch];
      // One 8-bit DMX step of the channel's range (16-bit ones are far finer).
      const double step = (spec.max - spec.min) / 255.0;
      ASSERT_TRUE(known[ch]);
      worst_error = std::max(worst_error, std::abs(measured[ch] - c.commanded()[ch]) / step);
    }
    if (tick % 5 == 0) send_junk(tick);
  }

  double worst_error = 0;  ///< in 8-bit DMX steps
  std::uint64_t junk_sent = 0;

 private:
  void send_junk(std::uint64_t tick) {
    std::vector<std::uint8_t> d(1 + (tick * 37) % 700);
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = static_cast<std::uint8_t>(tick * 131 + i * 7);
    // Every other junk datagram starts like a real packet of either protocol and then goes wrong.
    if (tick % 10 == 0 && d.size() > 20) {
      const char* id = "Art-Net";
      std::copy(id, id + 8, d.begin());
      d[8] = 0x00, d[9] = 0x50, d[10] = 0, d[11] = 14, d[16] = 0x02, d[17] = 0x01;  // odd length
    }
    (void)::sendto(fd_, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to_), sizeof to_);
    ++junk_sent;
  }

  const rig::Rig& rig_;
  assembly::FigureLinks& figure_;
  sim::SimDmxNode& node_;
  std::vector<std::size_t> channels_;
  int fd_ = -1;
  sockaddr_in to_{};
};

void play_network_rig(const std::string& rig_file, const char* expected_description) {
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/" + rig_file);
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/stage-lights.yaml");
  assembly::FigureLinks figure(rig, {});
  ASSERT_TRUE(figure.all_simulated());
  EXPECT_NE(figure.describe(1).find(expected_description), std::string::npos) << figure.describe(1);
  for (firmware_iface::ActuatorLink* link : figure.links()) ASSERT_EQ(link->start(), Status::ok);
  testing::SteppedFigureRun run(rig, show, figure);
  NetworkDmxWatch watch(rig, figure, 1);
  const control::RunResult result = run.run(watch);
  EXPECT_EQ(run.controller.latched_fault().cause, control::FaultCause::none);
  EXPECT_GT(result.ticks, 300U);             // 6 s at 50 Hz, plus soft start and stop
  EXPECT_LE(watch.worst_error, 0.5 + 1e-9);  // within half a DMX step every tick
  // All junk arrived (the node drains its socket each tick) and was counted, none taken.
  const sim::SimDmxNode& node = *figure.simulated_node(1);
  figure.advance(0.0);
  EXPECT_EQ(node.counters().bad_packets, watch.junk_sent);
  EXPECT_EQ(node.counters().out_of_order, 0U);
  EXPECT_GE(node.counters().packets, result.ticks);
  EXPECT_EQ(node.slot(1), 0);  // eye glow back at rest
}

TEST(NetworkDmxFigure, ArtnetRigPlaysItsShowThroughJunk) {
  play_network_rig("artnet-stage.yaml", "simulated Art-Net universe 1");
}

TEST(NetworkDmxFigure, SacnRigPlaysItsShowThroughJunk) {
  play_network_rig("sacn-stage.yaml", "simulated sACN universe 1 priority 120");
}

}  // namespace
}  // namespace avar
