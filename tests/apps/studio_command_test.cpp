// `avar studio` as a user runs it, a separate process on the simulated hello-head: it prints the
// URL, a WebSocket client edits and saves the show and asks it to stop; Ctrl-C eases to rest;
// bad options are refused before anything opens.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/child_process.hpp"
#include "../support/osc_sender.hpp"
#include "../support/cli_run.hpp"
#include "../support/studio_client.hpp"
#include "../support/temp_file.hpp"

namespace avar::app {
namespace {

const std::string kRig = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The port in the "studio: http://127.0.0.1:PORT/" line; 0 when there is none.
int port_in(const std::string& out) {
  const std::string marker = "studio: http://127.0.0.1:";
  const std::size_t at = out.find(marker);
  return at == std::string::npos ? 0 : std::stoi(out.substr(at + marker.size()));
}

/// Saves the show, then stops the studio, each answered.
void save_and_stop(testing::StudioClient& client) {
  client.send(R"({"type": "save"})");
  ASSERT_TRUE(client.next("saved"));
  client.send(R"({"type": "stop"})");
  ASSERT_TRUE(client.next("ok"));
}

TEST(StudioCommand, AClientEditsSavesAndStopsTheStudio) {
  const std::string original = read_all(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  const std::string show = testing::write_temp_file("show.yaml", original);
  testing::ChildProcess studio({AVAR_BINARY, "studio", show, "--rig", kRig, "--sim"});
  ASSERT_TRUE(studio.started());
  const int port = port_in(studio.read_out_until("e-stop"));
  ASSERT_GT(port, 0) << studio.out() << studio.err();
  {
    testing::StudioClient client(port, "/ws");
    ASSERT_TRUE(client.connected()) << client.error();
    ASSERT_TRUE(client.next("hello"));
    client.send(R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [2], "dt": 0, "dv": -10}]})");
    ASSERT_TRUE(client.next("ok"));
    save_and_stop(client);
  }
  EXPECT_EQ(studio.wait_for(std::chrono::seconds(20)), 0) << studio.err();
  EXPECT_NE(studio.out().find("stopped: a client asked; eased to rest"), std::string::npos) << studio.out();
  EXPECT_EQ(studio.err().find("not saved"), std::string::npos) << studio.err();
  const std::string saved = read_all(show);
  EXPECT_NE(saved, original);
  EXPECT_NE(saved.find("jaw"), std::string::npos);
}

TEST(StudioCommand, CtrlCEasesToRestAndWarnsOfUnsavedChanges) {
  const std::string show = testing::write_temp_file("show.yaml", read_all(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml"));
  testing::ChildProcess studio({AVAR_BINARY, "studio", show, "--rig", kRig, "--sim"});
  const int port = port_in(studio.read_out_until("e-stop"));
  ASSERT_GT(port, 0) << studio.out() << studio.err();
  {
    testing::StudioClient client(port, "/ws");
    ASSERT_TRUE(client.next("hello"));
    client.send(R"({"type": "edit", "edits": [{"op": "delete", "channel": "jaw", "keys": [1]}]})");
    ASSERT_TRUE(client.next("ok"));
  }
  studio.signal(SIGINT);
  EXPECT_EQ(studio.wait_for(std::chrono::seconds(20)), 130) << studio.err();
  EXPECT_NE(studio.out().find("stopped: eased to rest"), std::string::npos) << studio.out();
  EXPECT_NE(studio.err().find("warning: the show has changes that were not saved"), std::string::npos) << studio.err();
}

TEST(StudioCommand, ANewShowPathIsMadeWhenSaved) {
  const std::string show = testing::temp_path("new-show.yaml");
  testing::ChildProcess studio({AVAR_BINARY, "studio", show, "--rig", kRig, "--sim"});
  const int port = port_in(studio.read_out_until("e-stop"));
  ASSERT_GT(port, 0) << studio.out() << studio.err();
  {
    testing::StudioClient client(port, "/ws");
    const auto hello = client.next("hello");
    ASSERT_TRUE(hello);
    EXPECT_EQ((*hello)["show"]["name"], std::filesystem::path(show).stem().string());
    client.send(R"({"type": "edit", "edits": [{"op": "add", "channel": "jaw", "keys": [{"time": 1, "value": 10}]}]})");
    ASSERT_TRUE(client.next("ok"));
    save_and_stop(client);
  }
  EXPECT_EQ(studio.wait_for(std::chrono::seconds(20)), 0) << studio.err();
  EXPECT_NE(studio.err().find("new show: " + show + " is made when you save"), std::string::npos) << studio.err();
  EXPECT_NE(read_all(show).find("jaw"), std::string::npos);
}

TEST(StudioCommand, AnOscControlSteersTheShowsGazeTarget) {
  // The gaze head's show, paused at its start: the fly it looks at is to the right (y -0.8 m).
  const int osc_port = testing::free_udp_port();
  testing::ChildProcess studio({AVAR_BINARY, "studio", AVAR_SOURCE_DIR "/examples/shows/look-around.yaml", "--rig",
                                AVAR_SOURCE_DIR "/examples/rigs/gaze-head.yaml", "--sim", "--inputs",
                                AVAR_SOURCE_DIR "/examples/inputs/gaze-head-stick.yaml", "--input",
                                "osc://127.0.0.1:" + std::to_string(osc_port)});
  const int port = port_in(studio.read_out_until("e-stop"));
  ASSERT_GT(port, 0) << studio.out() << studio.err();
  testing::StudioClient client(port, "/ws");
  ASSERT_TRUE(client.next("hello"));
  testing::OscSender osc(osc_port);
  // 0.75 of gaze_y's range [-1.2, 1.2] m: 0.6 m to the left. The neck turns there.
  double y = 0, pan = 0;
  bool held = true;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline && !(std::abs(y - 0.6) < 1e-3 && pan > 20)) {
    ASSERT_TRUE(osc.send("/avar/control/gaze_y", 0.75f));
    const auto status = client.next("status");
    ASSERT_TRUE(status);
    y = (*status)["targets"][0]["point"][1].get<double>();
    held = (*status)["targets"][0]["held"].get<bool>();
    for (const auto& channel : (*status)["channels"])
      if (channel["name"] == "neck_pan") pan = channel["command"].get<double>();
  }
  EXPECT_NEAR(y, 0.6, 1e-3);
  EXPECT_GT(pan, 20);  // looking left, toward it
  EXPECT_FALSE(held);  // a live control, not a hand in the studio
  client.send(R"({"type": "stop"})");
  ASSERT_TRUE(client.next("ok"));
  EXPECT_EQ(studio.wait_for(std::chrono::seconds(20)), 0) << studio.err();
}

TEST(StudioCommand, BadOptionsAreRefusedBeforeAnythingOpens) {
  const auto listen = testing::run_avar({"studio", "--rig", kRig, "--sim", "--listen", "8080"});
  EXPECT_EQ(listen.code, 2);
  EXPECT_NE(listen.err.find("--listen '8080': expected HOST:PORT"), std::string::npos) << listen.err;
  const auto port = testing::run_avar({"studio", "--rig", kRig, "--sim", "--listen", "127.0.0.1:70000"});
  EXPECT_EQ(port.code, 2);
  const auto rig = testing::run_avar({"studio", "--rig", "no-such-rig.yaml", "--sim"});
  EXPECT_EQ(rig.code, 2);
  EXPECT_NE(rig.err.find("no-such-rig.yaml"), std::string::npos) << rig.err;
}

}  // namespace
}  // namespace avar::app
