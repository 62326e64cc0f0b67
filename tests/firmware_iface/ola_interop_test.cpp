// Interoperability with a real implementation: OLA's olad (Debian package `ola`) runs as a child
// process with its own config folder, HTTP and RPC ports, its Art-Net and E1.31 plugins on
// loopback and every other plugin off. avar's ArtnetLink and SacnLink send to it, and OLA's HTTP
// API (/get_dmx) must show the universes with the values commanded, 8- and 16-bit. Where olad
// cannot run (not installed, running as root without setpriv, the Art-Net or sACN port taken by
// another program), the test says why and skips. olad is killed when the test ends, whatever
// happens.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "../support/child_process.hpp"
#include "../support/temp_file.hpp"
#include "avar/firmware_iface/artnet_dmx_codec.hpp"
#include "avar/firmware_iface/network_dmx_link.hpp"

namespace avar::firmware_iface {
namespace {

using Clock = std::chrono::steady_clock;

/// A free port on loopback for `type` (SOCK_STREAM or SOCK_DGRAM), or 0.
int ola_free_port(int type) {
  const int fd = ::socket(AF_INET, type | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  int port = 0;
  if (fd >= 0 && ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0)
    port = ntohs(a.sin_port);
  if (fd >= 0) ::close(fd);
  return port;
}

/// Whether a UDP port can be bound on every interface right now (olad binds it so).
bool ola_udp_port_free(std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_ANY);
  a.sin_port = htons(port);
  const bool ok = fd >= 0 && ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  if (fd >= 0) ::close(fd);
  return ok;
}

/// One HTTP/1.0 request to 127.0.0.1:port; the body, or nullopt when nothing answered in 1 s.
std::optional<std::string> ola_http(int port, const std::string& method, const std::string& path, const std::string& form = "") {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return std::nullopt;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return std::nullopt;
  }
  std::string request = method + " " + path + " HTTP/1.0\r\nHost: 127.0.0.1\r\n";
  if (method == "POST")
    request += "Content-Type: application/x-www-form-urlencoded\r\nContent-Length: " + std::to_string(form.size()) + "\r\n";
  request += "\r\n" + form;
  if (::send(fd, request.data(), request.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(request.size())) {
    ::close(fd);
    return std::nullopt;
  }
  std::string response;
  std::array<char, 4096> buffer{};
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 1000) != 1) break;
    const ssize_t n = ::recv(fd, buffer.data(), buffer.size(), 0);
    if (n <= 0) break;
    response.append(buffer.data(), static_cast<std::size_t>(n));
  }
  ::close(fd);
  const auto body = response.find("\r\n\r\n");
  if (response.rfind("HTTP/1.", 0) != 0 || body == std::string::npos) return std::nullopt;
  return response.substr(body + 4);
}

/// olad in its own config folder, with only the Art-Net and E1.31 plugins, on loopback.
class OlaDaemon {
 public:
  /// Empty when olad runs; else why it cannot (for GTEST_SKIP).
  std::string start() {
    const std::string olad = "/usr/bin/olad";
    if (::access(olad.c_str(), X_OK) != 0) return "olad is not installed (Debian package ola)";
    if (!ola_udp_port_free(artnet::kUdpPort)) return "UDP port 6454 (Art-Net) is taken by another program";
    if (!ola_udp_port_free(sacn::kUdpPort)) return "UDP port 5568 (sACN) is taken by another program";
    dir_ = testing::temp_path("ola-config");
    std::filesystem::create_directories(dir_);
    write_configs();
    http_port_ = ola_free_port(SOCK_STREAM);
    const int rpc_port = ola_free_port(SOCK_STREAM);
    std::vector<std::string> args;
    if (::geteuid() == 0) {
      // olad refuses to run as root: run it as nobody, with a config folder nobody may write.
      if (::access("/usr/bin/setpriv", X_OK) != 0) return "olad refuses to run as root, and setpriv (util-linux) is missing";
      ::chmod(dir_.c_str(), 0777);
      for (const auto& f : std::filesystem::directory_iterator(dir_)) ::chmod(f.path().c_str(), 0666);
      args = {"/usr/bin/setpriv", "--reuid=nobody", "--regid=nogroup", "--clear-groups"};
    }
    args.insert(args.end(), {olad, "--config-dir", dir_, "--http-port", std::to_string(http_port_), "--rpc-port",
                             std::to_string(rpc_port), "--log-level", "1", "--no-register-with-dns-sd"});
    process_ = std::make_unique<testing::ChildProcess>(args);
    if (!process_->started()) return "olad could not be started";
    const auto deadline = Clock::now() + std::chrono::seconds(5);
    while (Clock::now() < deadline) {
      if (ola_http(http_port_, "GET", "/json/server_stats")) return "";
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return "olad's HTTP server did not answer within 5 s (olad failed to start)";
  }

  /// The id of the input port of the device whose name contains `device` ("ArtNet", "E1.31").
  std::string input_port(const std::string& device) const {
    const auto body = ola_http(http_port_, "GET", "/json/get_ports");
    if (!body) return "";
    for (const auto& p : nlohmann::json::parse(*body, nullptr, false))
      if (p.is_object() && !p.value("is_output", true) && p.value("device", "").find(device) != std::string::npos)
        return p.value("id", "");
    return "";
  }

  bool patch(int universe, const std::string& port) const {
    const auto body = ola_http(http_port_, "POST", "/new_universe",
                               "id=" + std::to_string(universe) + "&name=avar" + std::to_string(universe) + "&add_ports=" + port);
    if (!body) return false;
    const auto reply = nlohmann::json::parse(*body, nullptr, false);
    return reply.is_object() && reply.value("ok", false);
  }

  /// The universe's slots as olad has them now.
  std::vector<int> dmx(int universe) const {
    const auto body = ola_http(http_port_, "GET", "/get_dmx?u=" + std::to_string(universe));
    if (!body) return {};
    const auto reply = nlohmann::json::parse(*body, nullptr, false);
    if (!reply.is_object() || !reply.contains("dmx")) return {};
    return reply["dmx"].get<std::vector<int>>();
  }

 private:
  void write_configs() const {
    const auto write = [&](const std::string& plugin, const std::string& text) {
      std::ofstream(dir_ + "/ola-" + plugin + ".conf") << text;
    };
    write("artnet", "enabled = true\nip = 127.0.0.1\nuse_loopback = true\nnet = 0\nsubnet = 0\n");
    write("e131", "enabled = true\nip = 127.0.0.1\nignore_preview = true\ninput_ports = 1\noutput_ports = 1\n");
    for (const char* off : {"dummy",   "espnet",           "ftdidmx", "gpio",     "karate",    "kinet",     "milinst",
                            "opendmx", "openpixelcontrol", "osc",     "pathport", "renard",    "sandnet",   "shownet",
                            "spi",     "stageprofi",       "uartdmx", "usbdmx",   "usbserial", "dmx4linux", "nanoleaf"})
      write(off, "enabled = false\n");
  }

  std::string dir_;
  int http_port_ = 0;
  std::unique_ptr<testing::ChildProcess> process_;  ///< kills olad when destroyed
};

std::vector<DmxActuator> ola_test_actuators() {
  DmxActuator dimmer;  // channel 0: 0..100 % on slot 1
  dimmer.channel = 0;
  dimmer.address = 1;
  dimmer.calibration = {0, 100, 0, 255, false, 0};
  DmxActuator pan;  // channel 1: -90..90 deg on slots 3 (coarse) and 4 (fine)
  pan.channel = 1;
  pan.address = 3;
  pan.fine = true;
  pan.calibration = {-90, 90, 0, 65535, false, 0};
  return {dimmer, pan};
}

/// Sends `frame` every 20 ms until olad shows `expected` in its first slots, for up to 5 s.
bool ola_sees(const OlaDaemon& ola, NetworkDmxLink& link, int universe, const std::vector<int>& expected,
              std::vector<int>& seen) {
  const std::array<double, 2> frame{40.0, 30.0};
  const auto deadline = Clock::now() + std::chrono::seconds(5);
  while (Clock::now() < deadline) {
    if (link.send(frame) != Status::ok) return false;
    seen = ola.dmx(universe);
    if (seen.size() >= expected.size() && std::equal(expected.begin(), expected.end(), seen.begin())) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST(OlaInterop, OladReceivesTheUniversesAvarSendsOverArtNetAndSacn) {
  OlaDaemon ola;
  if (const std::string why = ola.start(); !why.empty()) GTEST_SKIP() << why;
  const std::string artnet_in = ola.input_port("ArtNet");
  const std::string e131_in = ola.input_port("E1.31");
  if (artnet_in.empty() || e131_in.empty()) GTEST_SKIP() << "olad's Art-Net or E1.31 plugin did not start (no input port listed)";
  ASSERT_TRUE(ola.patch(1, artnet_in));
  ASSERT_TRUE(ola.patch(2, e131_in));

  // 40 % -> 102; 30 deg -> 120/180 of 65535 = 43690 = 0xAAAA.
  const std::vector<int> expected{102, 0, 0xAA, 0xAA};
  std::vector<int> seen;

  ArtnetLinkConfig art;
  art.destination = parse_udp_destination("127.0.0.1", artnet::kUdpPort);
  art.port_address = artnet::port_address(0, 0, 1);  // OLA's Art-Net input port 0 on universe 1
  art.actuators = ola_test_actuators();
  ArtnetLink artnet_link(art);
  EXPECT_TRUE(ola_sees(ola, artnet_link, 1, expected, seen)) << "olad universe 1 holds " << ::testing::PrintToString(seen);

  SacnLinkConfig acn;
  acn.destination = parse_udp_destination("127.0.0.1", sacn::kUdpPort);
  acn.universe = 2;
  acn.source_name = "avar interop test";
  acn.actuators = ola_test_actuators();
  SacnLink sacn_link(acn);
  EXPECT_TRUE(ola_sees(ola, sacn_link, 2, expected, seen)) << "olad universe 2 holds " << ::testing::PrintToString(seen);
}

}  // namespace
}  // namespace avar::firmware_iface
