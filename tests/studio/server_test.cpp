// The studio's server end to end, as a program other than the page drives it: a WebSocket client
// (CivetWeb's) against a real-time session on the simulated hello-head figure. A slider's hold
// moves the simulated servo, a scrub moves show time, an edit comes back to every client, the
// token guards any address but loopback, and the HTTP API answers GET.
#include "avar/studio/server.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "support/studio_client.hpp"

namespace avar::studio {
namespace {

using nlohmann::json;
using testing::http_get;
using testing::StudioClient;
using namespace std::chrono_literals;

std::string example_file(const std::string& path) { return std::string(AVAR_SOURCE_DIR) + "/examples/" + path; }

/// The hello-head figure behind a studio server, its session running in real time on a thread
/// of its own until stopped.
struct ServedFigure {
  rig::Rig rig;
  Studio studio;
  session::ShowSession session;
  std::atomic<int> interrupts{0};
  std::optional<Server> server;
  std::thread runner;

  static session::SessionConfig config() {
    session::SessionConfig c;
    c.rate_hz = 100;
    c.links.simulate_all = true;
    c.hold_at_end = true;
    c.start_paused = true;
    c.realtime = {0, false, -1};
    return c;
  }
  explicit ServedFigure(ServerOptions options = {}, const std::string& rig_file = "rigs/hello-head.yaml",
                        const std::string& show_file = "shows/hello-head.yaml")
      : rig(config::load_rig_file(example_file(rig_file))),
        studio(rig, edit::ShowDocument(config::load_show_file(example_file(show_file))), ""),
        session(rig, studio.initial_show(), config()) {
    studio.attach(&session);
    session.add_observer(studio);
    EXPECT_FALSE(session.start_links());
    session.begin();
    server.emplace(studio, options);
    runner = std::thread([this] { (void)session.run(interrupts); });
  }
  ~ServedFigure() {
    session.stop();
    runner.join();
    server.reset();
    studio.attach(nullptr);
  }
  std::size_t channel(const std::string& name) const { return *rig.find_channel(name); }
};

TEST(StudioServer, ASliderMovesTheSimulatedServoAndAScrubMovesShowTime) {
  ServedFigure f;
  StudioClient client(f.server->port(), "/ws");
  ASSERT_TRUE(client.connected()) << client.error();
  const auto hello = client.next("hello");
  ASSERT_TRUE(hello);
  EXPECT_EQ((*hello)["rig"]["name"], "hello-head");
  EXPECT_EQ(f.server->clients(), 1u);

  const std::size_t jaw = f.channel("jaw");
  // The simulated servo settles within its pulse resolution of the command.
  client.send(R"({"type": "hold", "channel": "jaw", "value": 15})");
  const auto ok = client.next("ok");
  ASSERT_TRUE(ok);
  EXPECT_EQ((*ok)["request"], "hold");
  std::string jaw_seen;
  const auto there = client.wait_for([&](const json& m) {
    if (m["type"] == "status") jaw_seen = m["channels"][jaw].dump() + m["phase"].dump();
    return m["type"] == "status" && m["channels"][jaw]["measured"].is_number() &&
           std::abs(m["channels"][jaw]["measured"].get<double>() - 15.0) < 0.2;
  });
  ASSERT_TRUE(there) << "the simulated jaw did not reach 15: " << jaw_seen;
  EXPECT_EQ((*there)["channels"][jaw]["held"], true);

  client.send(R"({"type": "scrub", "time": 7.2})");
  std::string last;
  const auto scrubbed = client.wait_for([&](const json& m) {
    last = m.dump().substr(0, 300);
    return m["type"] == "status" && m["show_time"] == 7.2;
  });
  ASSERT_TRUE(scrubbed) << last;
  EXPECT_EQ((*scrubbed)["paused"], true);
}

TEST(StudioServer, AnEditGoesBackToEveryClientAndARefusalOnlyToItsSender) {
  ServedFigure f;
  StudioClient editor(f.server->port(), "/ws");
  StudioClient watcher(f.server->port(), "/ws");
  ASSERT_TRUE(editor.connected() && watcher.connected());
  ASSERT_TRUE(editor.next("hello"));
  ASSERT_TRUE(watcher.next("hello"));
  editor.send(R"({"type": "edit", "edits": [{"op": "move", "channel": "jaw", "keys": [2], "dt": 0, "dv": -10}]})");
  ASSERT_TRUE(editor.next("ok"));
  const auto seen = watcher.next("keys");
  ASSERT_TRUE(seen);
  EXPECT_EQ((*seen)["version"], 1);
  EXPECT_EQ((*seen)["tracks"][0]["channel"], "jaw");
  EXPECT_EQ((*seen)["tracks"][0]["keys"][0]["value"].get<double>(), 8.0);
  editor.send(R"({"type": "redo"})");
  const auto refused = editor.next("error");
  ASSERT_TRUE(refused);
  EXPECT_EQ((*refused)["message"], "message 'redo': there is nothing to redo");
  // The watcher hears of no refusal: its next change is the undo's.
  editor.send(R"({"type": "undo"})");
  const auto next = watcher.wait_for([](const json& m) { return m["type"] == "error" || m["type"] == "keys"; });
  ASSERT_TRUE(next);
  EXPECT_EQ((*next)["type"], "keys");
  EXPECT_EQ((*next)["version"], 2);
}

TEST(StudioServer, OffLoopbackEveryRequestNeedsTheToken) {
  ServerOptions options;
  options.host = "0.0.0.0";
  ServedFigure f(options);
  const std::string token = f.server->token();
  ASSERT_EQ(token.size(), 32u);
  EXPECT_NE(f.server->url().find("?token=" + token), std::string::npos);
  StudioClient stranger(f.server->port(), "/ws");
  EXPECT_FALSE(stranger.connected());
  StudioClient wrong(f.server->port(), "/ws?token=0123");
  EXPECT_FALSE(wrong.connected());
  StudioClient user(f.server->port(), "/ws?token=" + token);
  ASSERT_TRUE(user.connected()) << user.error();
  EXPECT_TRUE(user.next("hello"));
  EXPECT_EQ(http_get(f.server->port(), "/api/hello").first, "HTTP/1.0 403 Forbidden");
  const auto [status, body] = http_get(f.server->port(), "/api/hello?token=" + token);
  EXPECT_EQ(status, "HTTP/1.0 200 OK");
  EXPECT_EQ(json::parse(body)["type"], "hello");
}

TEST(StudioServer, ServesThePageFolderWithoutTheTokenAndTheConversationWithIt) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "avar-studio-page-test";
  std::filesystem::create_directories(dir);
  { std::ofstream(dir / "index.html") << "<!doctype html><title>page</title>"; }
  ServerOptions options;
  options.host = "0.0.0.0";
  options.assets_dir = dir.string();
  ServedFigure f(options);
  const auto [status, body] = http_get(f.server->port(), "/");
  EXPECT_EQ(status, "HTTP/1.0 200 OK");
  EXPECT_EQ(body, "<!doctype html><title>page</title>");
  EXPECT_EQ(http_get(f.server->port(), "/index.html").first, "HTTP/1.0 200 OK");
  EXPECT_EQ(http_get(f.server->port(), "/missing.js").first, "HTTP/1.0 404 Not Found");
  EXPECT_EQ(http_get(f.server->port(), "/api/hello").first, "HTTP/1.0 403 Forbidden");
  StudioClient stranger(f.server->port(), "/ws");
  EXPECT_FALSE(stranger.connected());
  std::filesystem::remove_all(dir);
}

TEST(StudioServer, AUrdfFiguresLooksAreInTheHelloAndItsMeshesServedByIndex) {
  ServerOptions options;
  options.host = "0.0.0.0";  // meshes are the figure's: behind the token like the rest of /api
  ServedFigure f(options, "rigs/urdf-head.yaml", "shows/look-around.yaml");
  const std::string token = "?token=" + f.server->token();
  const auto [status, body] = http_get(f.server->port(), "/api/hello" + token);
  ASSERT_EQ(status, "HTTP/1.0 200 OK");
  const json visuals = json::parse(body)["rig"]["kinematics"]["visuals"];
  ASSERT_EQ(visuals.size(), 7u);
  EXPECT_EQ(visuals[0]["shape"], "box");
  EXPECT_EQ(visuals[0]["joint"], nullptr);  // the base link: the base frame
  EXPECT_EQ(visuals[1]["shape"], "cylinder");
  EXPECT_DOUBLE_EQ(visuals[1]["length"].get<double>(), 0.26);
  const json& skull = visuals[3];
  EXPECT_EQ(skull["shape"], "mesh");
  EXPECT_EQ(skull["format"], "stl");
  EXPECT_EQ(skull["found"], true);
  EXPECT_EQ(skull["url"], "/api/mesh/3");
  EXPECT_EQ(skull["joint"], 1);  // tilt, the model's second joint
  EXPECT_EQ(visuals[6]["format"], "obj");
  const auto [mesh_status, mesh] = http_get(f.server->port(), "/api/mesh/3" + token);
  EXPECT_EQ(mesh_status, "HTTP/1.0 200 OK");
  EXPECT_EQ(mesh.size(), std::filesystem::file_size(example_file("rigs/urdf-head/meshes/head.stl")));
  EXPECT_EQ(mesh.substr(0, 29), "avar example: urdf-head skull");
  EXPECT_EQ(http_get(f.server->port(), "/api/mesh/3").first, "HTTP/1.0 403 Forbidden");
  // Only the rig's own meshes, by index: a box, a number past the end, a path are not files.
  EXPECT_EQ(http_get(f.server->port(), "/api/mesh/0" + token).first, "HTTP/1.0 404 Not Found");
  EXPECT_EQ(http_get(f.server->port(), "/api/mesh/7" + token).first, "HTTP/1.0 404 Not Found");
  EXPECT_EQ(http_get(f.server->port(), "/api/mesh/..%2f..%2fetc%2fpasswd" + token).first, "HTTP/1.0 404 Not Found");
}

TEST(StudioServer, TheHttpApiAnswersGet) {
  ServedFigure f;
  EXPECT_TRUE(f.server->token().empty());
  EXPECT_EQ(f.server->url(), "http://127.0.0.1:" + std::to_string(f.server->port()) + "/");
  const auto [hello_status, hello] = http_get(f.server->port(), "/api/hello");
  EXPECT_EQ(hello_status, "HTTP/1.0 200 OK");
  EXPECT_EQ(json::parse(hello)["show"]["name"], "hello-head");
  // Once the figure has ticked, the status has its channels.
  StudioClient client(f.server->port(), "/ws");
  ASSERT_TRUE(client.next("status"));
  const auto [status_line, status] = http_get(f.server->port(), "/api/status");
  EXPECT_EQ(status_line, "HTTP/1.0 200 OK");
  EXPECT_EQ(json::parse(status)["type"], "status");
  EXPECT_EQ(json::parse(status)["channels"].size(), f.rig.channels.size());
  EXPECT_EQ(http_get(f.server->port(), "/api/nothing").first, "HTTP/1.0 404 Not Found");
  EXPECT_EQ(http_get(f.server->port(), "/").first, "HTTP/1.0 404 Not Found");
}

TEST(StudioServer, AnAddressInUseIsNamed) {
  ServedFigure f;
  ServerOptions taken;
  taken.port = f.server->port();
  try {
    Server second(f.studio, taken);
    FAIL() << "a second server listened on the same port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(taken.port)), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace avar::studio
