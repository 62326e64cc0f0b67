// `avar play --osc-control`: the OSC control surface end to end over loopback, against the built
// binary: play, seek, state replies, stop; bad messages answered and ignored; the e-stop.
#include <gtest/gtest.h>

#include <cstring>
#include <lo/lo.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "../support/child_process.hpp"
#include "../support/osc_sender.hpp"
#include "../support/temp_file.hpp"
#include "../support/udp_sender.hpp"

namespace avar::app {
namespace {

const std::string kOscShow = AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml";
const std::string kOscRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

struct OscReply {
  std::string path;
  std::string phase;  ///< /avar/state's first argument, or /avar/error's text
  float show_time = 0;
};

/// A liblo server on a free loopback port: sends from it (so replies come back to it) and
/// collects the replies.
class OscControlClient {
 public:
  OscControlClient() : server_(lo_server_new_with_proto(nullptr, LO_UDP, nullptr)) {
    lo_server_add_method(server_, nullptr, nullptr, &OscControlClient::on_message, this);
  }
  ~OscControlClient() {
    if (target_) lo_address_free(target_);
    lo_server_free(server_);
  }
  OscControlClient(const OscControlClient&) = delete;
  OscControlClient& operator=(const OscControlClient&) = delete;

  void target(int port) { target_ = lo_address_new("127.0.0.1", std::to_string(port).c_str()); }
  lo_address address() const { return target_; }
  lo_server server() const { return server_; }

  /// Waits up to two seconds for the next reply.
  std::optional<OscReply> next() {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (replies_.empty() && std::chrono::steady_clock::now() < deadline) lo_server_recv_noblock(server_, 20);
    if (replies_.empty()) return std::nullopt;
    OscReply r = replies_.front();
    replies_.erase(replies_.begin());
    return r;
  }

 private:
  static int on_message(const char* path, const char* types, lo_arg** argv, int argc, lo_message, void* user) {
    auto* self = static_cast<OscControlClient*>(user);
    OscReply r;
    r.path = path;
    // liblo's arguments are 4-byte aligned, not as lo_arg's union (8): read the bytes.
    if (argc >= 1 && types[0] == LO_STRING) r.phase = reinterpret_cast<const char*>(argv[0]);
    if (argc >= 2 && types[1] == LO_FLOAT) {
      float v = 0;
      std::memcpy(&v, argv[1], sizeof v);
      r.show_time = v;
    }
    self->replies_.push_back(r);
    return 0;
  }

  lo_server server_;
  lo_address target_ = nullptr;
  std::vector<OscReply> replies_;
};

std::vector<std::string> osc_play_args(int port) {
  return {AVAR_BINARY,
          "play",
          kOscShow,
          "--rig",
          kOscRig,
          "--sim",
          "--rate",
          "100",
          "--no-progress",
          "--priority",
          "0",
          "--no-lock-memory",
          "--osc-control",
          "127.0.0.1:" + std::to_string(port)};
}

TEST(OscControl, PlaySeekStateAndStopOverLoopback) {
  const int port = testing::free_udp_port();
  testing::ChildProcess play(osc_play_args(port));
  ASSERT_TRUE(play.started());
  ASSERT_NE(play.read_err_until("waiting for /avar/show/play").find("OSC control on udp 127.0.0.1:" + std::to_string(port)),
            std::string::npos)
      << play.err();
  OscControlClient client;
  client.target(port);

  // Junk and mistakes are answered with /avar/error and change nothing.
  testing::UdpSender raw;
  const std::vector<std::uint8_t> junk{'x', 'y', 'z'};
  ASSERT_TRUE(raw.send(port, junk));  // no reply possible to this sender's socket: just counted
  lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/show/play", "s", "another-show");
  auto r = client.next();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->path, "/avar/error");
  EXPECT_NE(r->phase.find("'hello-head'"), std::string::npos) << r->phase;
  lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/show/seek", "s", "soon");
  r = client.next();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->path, "/avar/error");
  lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/dance", "");
  r = client.next();
  ASSERT_TRUE(r);
  EXPECT_NE(r->phase.find("unknown address /avar/dance"), std::string::npos) << r->phase;

  // Waiting at the first frame until told to play (polled: homing ends when it ends).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(4);
  std::string phase;
  while (phase != "waiting" && std::chrono::steady_clock::now() < deadline) {
    lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/state", "");
    r = client.next();
    ASSERT_TRUE(r);
    phase = r->phase;
  }
  ASSERT_EQ(phase, "waiting");
  EXPECT_FLOAT_EQ(r->show_time, 0.0F);

  lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/show/play", "s", "hello-head");
  r = client.next();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->path, "/avar/state");
  lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/show/seek", "f", 8.0F);
  ASSERT_TRUE(client.next());
  // The play and the seek show in the state within a few ticks (polled every 5 ms).
  float show_time = 0;
  phase.clear();
  const auto seek_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while ((phase != "running" || show_time < 8.0F) && std::chrono::steady_clock::now() < seek_deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/state", "");
    r = client.next();
    ASSERT_TRUE(r);
    show_time = r->show_time;
    phase = r->phase;
  }
  EXPECT_EQ(phase, "running");
  EXPECT_GE(show_time, 8.0F);
  EXPECT_LT(show_time, 9.0F);

  lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/show/stop", "");
  r = client.next();
  ASSERT_TRUE(r);
  EXPECT_EQ(play.wait(), 0) << play.err();
  EXPECT_NE(play.out().find("commands, 4 ignored"), std::string::npos) << play.out();
}

TEST(OscControl, EstopFaultsTheRun) {
  const int port = testing::free_udp_port();
  testing::ChildProcess play(osc_play_args(port));
  ASSERT_TRUE(play.started());
  play.read_err_until("waiting for /avar/show/play");
  OscControlClient client;
  client.target(port);
  lo_send_from(client.address(), client.server(), LO_TT_IMMEDIATE, "/avar/estop", "");
  ASSERT_TRUE(client.next());
  EXPECT_EQ(play.wait(), 3) << play.err();
  EXPECT_NE(play.err().find("e-stop; actuators took their fail-safe actions"), std::string::npos) << play.err();
}

}  // namespace
}  // namespace avar::app
