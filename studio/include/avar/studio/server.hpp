#pragma once
// The studio behind HTTP and WebSocket (CivetWeb): a client connects to /ws, gets the "hello"
// message, sends the protocol's messages and gets the replies, every change of the show, and the
// figure's status several times a second. /api/hello and /api/status answer the same over plain
// HTTP GET; the built page, when there is one, is served from its folder.
//
// Security: on a loopback address anyone on this machine may connect, as with any local tool.
// On any other address every request needs the token the server makes (`?token=...`, printed
// in the URL): the studio moves a figure.
//
// Threads: CivetWeb's workers run the handlers; one thread of the server's own sends status.
// Not real-time.

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "avar/studio/studio.hpp"

struct mg_context;
struct mg_connection;

namespace avar::studio {

struct ServerOptions {
  std::string host = "127.0.0.1";  ///< the address to listen on
  int port = 0;                    ///< 0: a free port, chosen by the system
  std::string assets_dir;          ///< the built page; empty: the API and WebSocket only
  double status_hz = 20;           ///< status messages a second, 1 to 100
};

/// Whether `host` is a loopback address (no token is needed there).
bool is_loopback(const std::string& host);

class Server {
 public:
  /// Listens and serves `studio` (borrowed; outlives the server). std::invalid_argument for a
  /// bad option, std::runtime_error naming the address when it cannot listen there.
  Server(Studio& studio, ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  int port() const noexcept { return port_; }
  /// The token every request needs; empty on a loopback address.
  const std::string& token() const noexcept { return token_; }
  /// The page's address, token included: what a user opens.
  std::string url() const;
  /// WebSocket clients connected now.
  std::size_t clients() const;

 private:
  friend struct ServerCallbacks;
  bool authorised(const mg_connection* conn) const;
  void send(mg_connection* conn, const std::string& text);
  void broadcast(const std::string& text);
  void status_loop();

  Studio& studio_;
  ServerOptions options_;
  std::string token_;
  int port_ = 0;
  mg_context* context_ = nullptr;
  mutable std::mutex clients_mutex_;  // clients_, and every write to a client
  std::set<mg_connection*> clients_;
  std::atomic<bool> stopping_{false};
  std::thread status_thread_;
};

}  // namespace avar::studio
