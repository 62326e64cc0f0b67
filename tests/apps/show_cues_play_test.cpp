// Cues end to end: `avar play --fast` plays the stage show on the Art-Net example rig; its OSC
// cues arrive over loopback UDP, once each, with their arguments, and its digital cues switch
// the strobe through the normal channel path (commanded and simulated on their ticks).

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/osc_sender.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

std::string cues_read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// OSC bytes of a string: the characters, a NUL, padded to a multiple of 4.
std::string cues_osc_string(const std::string& s) {
  std::string out = s + '\0';
  while (out.size() % 4 != 0) out += '\0';
  return out;
}

std::string cues_be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

TEST(ShowCuesPlay, OscCuesArriveOnceAndDigitalCuesSwitchTheStrobe) {
  const int port = testing::free_udp_port();
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a), 0);

  std::string show = cues_read_text(AVAR_SOURCE_DIR "/examples/shows/stage-lights.yaml");
  for (auto at = show.find("127.0.0.1:9000"); at != std::string::npos; at = show.find("127.0.0.1:9000"))
    show.replace(at, 14, "127.0.0.1:" + std::to_string(port));
  const std::string show_path = testing::write_temp_file("stage-cues.yaml", show);
  const std::string trace = testing::temp_path("cues-trace.csv");
  const testing::CliResult r = testing::run_avar(
      {"play", show_path, "--rig", AVAR_SOURCE_DIR "/examples/rigs/artnet-stage.yaml", "--fast", "--trace", trace});
  ASSERT_EQ(r.code, kExitOk) << r.err << r.out;
  EXPECT_NE(r.err.find("cues: 2 OSC message(s) sent, 0 failed"), std::string::npos) << r.err;

  std::vector<std::string> received;
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, received.size() < 2 ? 2000 : 50) != 1) break;
    char buffer[1024];
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    received.emplace_back(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  ASSERT_EQ(received.size(), 2U);
  const std::string wake = cues_osc_string("/stage/scene") + cues_osc_string(",is") + cues_be32(1) + cues_osc_string("wake");
  const float half = 0.5F;
  std::uint32_t bits = 0;
  std::memcpy(&bits, &half, 4);
  const std::string scene2 = cues_osc_string("/stage/scene") + cues_osc_string(",if") + cues_be32(2) + cues_be32(bits);
  EXPECT_EQ(received[0], wake);
  EXPECT_EQ(received[1], scene2);

  // The strobe: on for 0.2 s (10 ticks at 50 Hz), commanded and seen by the simulated node.
  const auto rows = testing::csv_rows(cues_read_text(trace));
  ASSERT_GT(rows.size(), 300U);
  const auto& header = rows.front();
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t command = column("strobe.command"), measured = column("strobe.measured");
  ASSERT_LT(measured, header.size());
  int on = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double c = std::stod(rows[i][command]);
    ASSERT_TRUE(c == 0.0 || c == 1.0) << c;
    on += c == 1.0 ? 1 : 0;
    EXPECT_EQ(std::stod(rows[i][measured]), c) << "row " << i;
  }
  EXPECT_EQ(on, 10);
}

}  // namespace
}  // namespace avar::app
