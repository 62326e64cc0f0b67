#include "avar/studio/server.hpp"

#include <civetweb.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace avar::studio {
namespace {

/// 128 bits from the system's random source, as hex.
std::string make_token() {
  std::random_device random;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 8; ++i) {
    const unsigned v = random() & 0xffffu;
    for (int shift = 12; shift >= 0; shift -= 4) token += kHex[(v >> shift) & 0xfu];
  }
  return token;
}

/// Comparison in time independent of where the strings first differ.
bool same_secret(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

/// One WebSocket client's message being assembled from its frames.
struct Partial {
  std::string text;
};

}  // namespace

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host == "[::1]" || host.rfind("127.", 0) == 0;
}

/// CivetWeb's C callbacks, each handing over to the server.
struct ServerCallbacks {
  static Server& of(void* data) { return *static_cast<Server*>(data); }

  static int log_message(const mg_connection*, const char*) { return 1; }  // errors come back as values

  static int ws_connect(const mg_connection* conn, void* data) {
    // Nonzero refuses the connection.
    return of(data).authorised(conn) ? 0 : 1;
  }

  static void ws_ready(mg_connection* conn, void* data) {
    Server& server = of(data);
    mg_set_user_connection_data(conn, new Partial);
    {
      const std::lock_guard lock(server.clients_mutex_);
      server.clients_.insert(conn);
    }
    server.send(conn, server.studio_.hello());
  }

  static int ws_data(mg_connection* conn, int bits, char* data, std::size_t length, void* user) {
    Server& server = of(user);
    const int opcode = bits & 0xf;
    if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
    if (opcode != MG_WEBSOCKET_OPCODE_TEXT && opcode != MG_WEBSOCKET_OPCODE_CONTINUATION) return 1;
    auto* partial = static_cast<Partial*>(mg_get_user_connection_data(conn));
    if (!partial) return 0;
    partial->text.append(data, length);
    if ((bits & 0x80) == 0) return 1;  // more frames of this message to come
    const Replies replies = server.studio_.handle(partial->text);
    partial->text.clear();
    // The change first: a client that hears its "ok" already holds the show it made.
    for (const std::string& m : replies.to_all) server.broadcast(m);
    server.send(conn, replies.to_sender);
    return 1;
  }

  static void ws_close(const mg_connection* conn, void* data) {
    Server& server = of(data);
    {
      const std::lock_guard lock(server.clients_mutex_);
      server.clients_.erase(const_cast<mg_connection*>(conn));
    }
    delete static_cast<Partial*>(mg_get_user_connection_data(conn));
  }

  static int api(mg_connection* conn, void* data) {
    Server& server = of(data);
    const mg_request_info* request = mg_get_request_info(conn);
    if (!server.authorised(conn)) {
      mg_send_http_error(conn, 403, "%s", "the studio needs its token: open the URL it printed\n");
      return 403;
    }
    if (std::strcmp(request->request_method, "GET") != 0) {
      mg_send_http_error(conn, 405, "%s", "the studio's API answers GET; send messages over /ws\n");
      return 405;
    }
    const std::string_view uri = request->local_uri ? request->local_uri : "";
    std::string body;
    if (uri == "/api/hello") {
      body = server.studio_.hello();
    } else if (uri == "/api/status") {
      body = server.studio_.status();
    } else if (uri.substr(0, kMeshPrefix.size()) == kMeshPrefix) {
      return send_mesh(server, conn, uri.substr(kMeshPrefix.size()));
    } else {
      mg_send_http_error(conn, 404, "%s", "no such API: /api/hello, /api/status or /api/mesh/N\n");
      return 404;
    }
    mg_send_http_ok(conn, "application/json", static_cast<long long>(body.size()));
    mg_write(conn, body.data(), body.size());
    return 200;
  }

  static constexpr std::string_view kMeshPrefix = "/api/mesh/";

  /// The rig's mesh file by its visual's index (only files the rig names: no path comes from
  /// the client).
  static int send_mesh(Server& server, mg_connection* conn, std::string_view digits) {
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    const std::optional<std::string> file =
        ec == std::errc() && end == digits.data() + digits.size() ? server.studio_.mesh_file(index) : std::nullopt;
    if (!file) {
      mg_send_http_error(conn, 404, "%s", "no such mesh: /api/mesh/N names a mesh visual of the rig whose file exists\n");
      return 404;
    }
    mg_send_mime_file(conn, file->c_str(), "application/octet-stream");
    return 200;
  }

  static int page(mg_connection* conn, void* data) {
    // The page's files need no token: they hold no show and move nothing; the page passes the
    // token it was opened with on to /ws.
    Server& server = of(data);
    if (server.options_.assets_dir.empty()) {
      mg_send_http_error(conn, 404, "%s",
                         "this studio serves no page: /ws speaks the studio protocol, /api/hello and "
                         "/api/status answer GET\n");
      return 404;
    }
    return 0;  // CivetWeb serves the file from the page's folder
  }
};

Server::Server(Studio& studio, ServerOptions options) : studio_(studio), options_(std::move(options)) {
  if (!(options_.status_hz >= 1 && options_.status_hz <= 100))
    throw std::invalid_argument("the studio's status rate must be 1 to 100 messages a second");
  if (options_.port < 0 || options_.port > 65535) throw std::invalid_argument("a port is 0 to 65535");
  if (options_.host.empty()) throw std::invalid_argument("the studio needs an address to listen on");
  if (!is_loopback(options_.host)) token_ = make_token();
  const bool v6 = options_.host.find(':') != std::string::npos && options_.host.front() != '[';
  const std::string listen = (v6 ? "[" + options_.host + "]" : options_.host) + ":" + std::to_string(options_.port);
  // No Nagle: a reply or a status is a few small writes (frame header, payload) that must not
  // wait for the client's delayed acknowledgement.
  std::vector<const char*> config = {"listening_ports",          listen.c_str(), "num_threads", "8",
                                     "enable_directory_listing", "no",           "tcp_nodelay", "1"};
  if (!options_.assets_dir.empty()) {
    config.push_back("document_root");
    config.push_back(options_.assets_dir.c_str());
  }
  config.push_back(nullptr);
  mg_init_library(0);
  mg_callbacks callbacks{};
  callbacks.log_message = &ServerCallbacks::log_message;
  context_ = mg_start(&callbacks, this, config.data());
  if (!context_)
    throw std::runtime_error("the studio cannot listen on " + listen + ": the address is in use or not this machine's");
  mg_server_port ports[1];
  if (mg_get_server_ports(context_, 1, ports) < 1) {
    mg_stop(context_);
    throw std::runtime_error("the studio cannot tell which port it listens on");
  }
  port_ = ports[0].port;
  mg_set_websocket_handler(context_, "/ws", &ServerCallbacks::ws_connect, &ServerCallbacks::ws_ready, &ServerCallbacks::ws_data,
                           &ServerCallbacks::ws_close, this);
  mg_set_request_handler(context_, "/api/", &ServerCallbacks::api, this);
  mg_set_request_handler(context_, "/", &ServerCallbacks::page, this);
  status_thread_ = std::thread([this] { status_loop(); });
}

Server::~Server() {
  stopping_.store(true);
  if (status_thread_.joinable()) status_thread_.join();
  mg_stop(context_);
}

bool Server::authorised(const mg_connection* conn) const {
  if (token_.empty()) return true;
  const mg_request_info* request = mg_get_request_info(conn);
  if (!request || !request->query_string) return false;
  char given[64] = {};
  const int n = mg_get_var(request->query_string, std::strlen(request->query_string), "token", given, sizeof given);
  return n > 0 && same_secret(std::string_view(given, static_cast<std::size_t>(n)), token_);
}

std::string Server::url() const {
  const bool v6 = options_.host.find(':') != std::string::npos && options_.host.front() != '[';
  std::string url = "http://" + (v6 ? "[" + options_.host + "]" : options_.host) + ":" + std::to_string(port_) + "/";
  if (!token_.empty()) url += "?token=" + token_;
  return url;
}

std::size_t Server::clients() const {
  const std::lock_guard lock(clients_mutex_);
  return clients_.size();
}

void Server::send(mg_connection* conn, const std::string& text) {
  if (text.empty()) return;
  const std::lock_guard lock(clients_mutex_);
  if (clients_.count(conn) == 0) return;  // closed meanwhile
  (void)mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size());
}

void Server::broadcast(const std::string& text) {
  const std::lock_guard lock(clients_mutex_);
  for (mg_connection* conn : clients_) (void)mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size());
}

void Server::status_loop() {
  const auto period = std::chrono::duration<double>(1.0 / options_.status_hz);
  auto next = std::chrono::steady_clock::now();
  while (!stopping_.load()) {
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
    std::this_thread::sleep_until(next);
    if (clients() == 0) continue;
    for (const std::string& m : studio_.take_status()) broadcast(m);
  }
}

}  // namespace avar::studio
