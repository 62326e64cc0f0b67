#pragma once
// A client of the studio's server for tests: CivetWeb's WebSocket client keeping every message it
// gets, and a plain HTTP/1.0 GET. Link CivetWeb and nlohmann-json. Shared with the benchmarks: no
// GoogleTest here.
#include <arpa/inet.h>
#include <civetweb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

namespace avar::testing {

/// A WebSocket client that keeps every message it gets.
class StudioClient {
 public:
  /// Connects to ws://127.0.0.1:port + path; connected() says whether it did.
  StudioClient(int port, const std::string& path) {
    char error[256] = {};
    conn_ = mg_connect_websocket_client("127.0.0.1", port, 0, error, sizeof error, path.c_str(), nullptr, &StudioClient::data,
                                        &StudioClient::closed, this);
    error_ = error;
    if (conn_) no_delay_towards(port);
  }
  ~StudioClient() {
    if (conn_) mg_close_connection(conn_);
  }
  StudioClient(const StudioClient&) = delete;
  StudioClient& operator=(const StudioClient&) = delete;
  bool connected() const { return conn_ != nullptr; }
  const std::string& error() const { return error_; }

  /// Sends one text message; false when it could not be written.
  bool send(const std::string& text) {
    return conn_ && mg_websocket_client_write(conn_, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size()) > 0;
  }
  /// The next message of `type` (others before it are dropped), within 5 s.
  std::optional<nlohmann::json> next(const std::string& type) {
    return wait_for([&](const nlohmann::json& m) { return m["type"] == type; });
  }
  /// The first message, from now on, that `accept` takes, within 5 s.
  std::optional<nlohmann::json> wait_for(const std::function<bool(const nlohmann::json&)>& accept) {
    std::unique_lock lock(mutex_);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    for (;;) {
      while (!inbox_.empty()) {
        nlohmann::json m = nlohmann::json::parse(inbox_.front());
        inbox_.pop_front();
        if (accept(m)) return m;
      }
      if (arrived_.wait_until(lock, deadline) == std::cv_status::timeout && inbox_.empty()) return std::nullopt;
    }
  }

 private:
  /// TCP_NODELAY on this process's connections to `port`, as browsers set it on theirs: CivetWeb's
  /// client writes a frame's header and payload apart, and without it the payload would wait
  /// for the server's delayed acknowledgement (up to 40 ms). CivetWeb does not hand out its
  /// socket, so the process's sockets are looked through.
  static void no_delay_towards(int port) {
    for (int fd = 3; fd < 1024; ++fd) {
      sockaddr_in peer{};
      socklen_t size = sizeof peer;
      if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &size) != 0 || peer.sin_family != AF_INET ||
          ntohs(peer.sin_port) != port)
        continue;
      const int on = 1;
      (void)::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    }
  }

  static int data(mg_connection*, int bits, char* data, std::size_t length, void* user) {
    auto* self = static_cast<StudioClient*>(user);
    if ((bits & 0xf) != MG_WEBSOCKET_OPCODE_TEXT) return 1;
    {
      const std::lock_guard lock(self->mutex_);
      self->inbox_.emplace_back(data, length);
    }
    self->arrived_.notify_all();
    return 1;
  }
  static void closed(const mg_connection*, void*) {}

  mg_connection* conn_ = nullptr;
  std::string error_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<std::string> inbox_;
};

/// GET `target` from 127.0.0.1:port over plain HTTP/1.0: the status line and the body.
inline std::pair<std::string, std::string> http_get(int port, const std::string& target) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return {"no connection", ""};
  }
  const std::string request = "GET " + target + " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
  (void)::write(fd, request.data(), request.size());
  std::string response;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) response.append(buffer, static_cast<std::size_t>(n));
  ::close(fd);
  const std::size_t line_end = response.find("\r\n");
  const std::size_t body = response.find("\r\n\r\n");
  return {response.substr(0, line_end), body == std::string::npos ? "" : response.substr(body + 4)};
}

}  // namespace avar::testing
