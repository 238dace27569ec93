#include "monitor/display.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>
#include <string>

#include "core/error.h"

namespace moorsim::monitor {
namespace {

/// The most a request may hold, and the most kept unsent for a client [bytes].
constexpr std::size_t kMaxRequest = 8192;
constexpr std::size_t kMaxPending = 4 << 20;

std::string Response(int status, std::string_view reason, std::string_view type,
                     std::string_view body) {
  std::string r = "HTTP/1.1 " + std::to_string(status) + " " + std::string(reason) + "\r\n";
  r += "Content-Type: " + std::string(type) + "\r\n";
  r += "Content-Length: " + std::to_string(body.size()) + "\r\n";
  r += "Cache-Control: no-store\r\nConnection: close\r\n";
  // The page runs nothing it did not get from here.
  r += "Content-Security-Policy: default-src 'self'\r\n\r\n";
  r += body;
  return r;
}

std::string Error(int status, std::string_view reason) {
  return Response(status, reason, "text/plain; charset=utf-8", std::string(reason) + "\n");
}

}  // namespace

struct DisplayServer::Impl {
  struct Client {
    std::string request;
    std::string pending;   // bytes to send
    bool events = false;   // an event stream: kept open
    bool closing = false;  // close once `pending` is sent
  };

  Poller* poller = nullptr;
  int listener = -1;
  int port = 0;
  std::function<std::string()> state;
  std::function<bool(int)> acknowledge;
  std::map<int, Client> clients;
  std::chrono::steady_clock::time_point last_publish = std::chrono::steady_clock::now();

  ~Impl() {
    for (auto& [fd, client] : clients) {
      poller->Remove(fd);
      ::close(fd);
    }
    if (listener >= 0) {
      poller->Remove(listener);
      ::close(listener);
    }
  }

  void Accept() {
    for (int i = 0; i < 16; ++i) {
      const int fd = ::accept4(listener, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (fd < 0) return;
      clients[fd] = Client{};
      poller->Add(fd, POLLIN, [this, fd](short revents) { Ready(fd, revents); });
    }
  }

  void Drop(int fd) {
    poller->Remove(fd);
    ::close(fd);
    clients.erase(fd);
  }

  void Ready(int fd, short revents) {
    const auto found = clients.find(fd);
    if (found == clients.end()) return;
    Client& c = found->second;
    if (revents & (POLLERR | POLLNVAL)) return Drop(fd);
    if (revents & POLLIN) {
      char buffer[4096];
      const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
      if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) return Drop(fd);
      if (n > 0 && !c.events && !c.closing) {
        c.request.append(buffer, static_cast<std::size_t>(n));
        if (c.request.find("\r\n\r\n") != std::string::npos) {
          Handle(c);
        } else if (c.request.size() > kMaxRequest) {
          Reply(c, Error(400, "Bad Request"));
        }
      }
    }
    if (revents & POLLHUP) return Drop(fd);
    Flush(fd);
  }

  void Reply(Client& c, std::string response) {
    c.pending += response;
    c.closing = true;
  }

  void Handle(Client& c) {
    const std::size_t line_end = c.request.find("\r\n");
    const std::string line = c.request.substr(0, line_end);
    const std::size_t space1 = line.find(' ');
    const std::size_t space2 = line.find(' ', space1 + 1);
    if (space1 == std::string::npos || space2 == std::string::npos ||
        line.compare(space2 + 1, 5, "HTTP/") != 0) {
      return Reply(c, Error(400, "Bad Request"));
    }
    const std::string method = line.substr(0, space1);
    std::string path = line.substr(space1 + 1, space2 - space1 - 1);
    if (const std::size_t query = path.find('?'); query != std::string::npos) path.resize(query);
    if (method == "GET" && path == "/api/state") {
      return Reply(c, Response(200, "OK", "application/json", state()));
    }
    if (method == "GET" && path == "/api/events") {
      c.events = true;
      c.pending +=
          "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\n"
          "Connection: keep-alive\r\n\r\n";
      c.pending += "data: " + state() + "\n\n";
      return;
    }
    if (path.rfind("/api/ack/", 0) == 0) {
      if (method != "POST") return Reply(c, Error(405, "Method Not Allowed"));
      // Only the page itself: a request from another site's page cannot carry this header
      // without the browser asking first (CORS), which is never granted.
      std::string headers = c.request.substr(0, c.request.find("\r\n\r\n"));
      std::transform(headers.begin(), headers.end(), headers.begin(),
                     [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
      if (headers.find("\r\nx-moorsim-acknowledge: yes") == std::string::npos) {
        return Reply(c, Error(403, "Forbidden"));
      }
      const std::string number = path.substr(9);
      const bool digits = !number.empty() && number.size() <= 3 &&
                          number.find_first_not_of("0123456789") == std::string::npos;
      if (!digits) return Reply(c, Error(404, "Not Found"));
      const bool done = acknowledge(std::stoi(number));
      return Reply(c, Response(200, "OK", "application/json",
                               done ? "{\"acknowledged\":true}" : "{\"acknowledged\":false}"));
    }
    if (method != "GET") return Reply(c, Error(405, "Method Not Allowed"));
    const Asset* asset = FindAsset(path == "/" ? "index.html" : path.substr(1));
    if (asset == nullptr) return Reply(c, Error(404, "Not Found"));
    Reply(c, Response(200, "OK", asset->type, asset->body));
  }

  void Flush(int fd) {
    const auto found = clients.find(fd);
    if (found == clients.end()) return;
    Client& c = found->second;
    while (!c.pending.empty()) {
      const ssize_t n = ::send(fd, c.pending.data(), c.pending.size(), MSG_NOSIGNAL);
      if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK) break;
        return Drop(fd);
      }
      c.pending.erase(0, static_cast<std::size_t>(n));
    }
    if (c.pending.size() > kMaxPending) return Drop(fd);  // it has stopped reading
    if (c.pending.empty() && c.closing) return Drop(fd);
    poller->Add(fd, c.pending.empty() ? POLLIN : POLLIN | POLLOUT,
                [this, fd](short revents) { Ready(fd, revents); });
  }
};

DisplayServer::DisplayServer(const scenarios::DisplayConfig& config, Poller* poller,
                             std::function<std::string()> state,
                             std::function<bool(int)> acknowledge)
    : impl_(std::make_unique<Impl>()) {
  impl_->poller = poller;
  impl_->state = std::move(state);
  impl_->acknowledge = std::move(acknowledge);
  sockaddr_in local = ResolveIpv4(config.address, config.port, "display.address");
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0 ||
      ::listen(fd, 16) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw InputError("display: cannot serve on " + config.address + ":" +
                     std::to_string(config.port) + ": " + why);
  }
  socklen_t size = sizeof local;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &size);
  impl_->port = ntohs(local.sin_port);
  impl_->listener = fd;
  Impl* impl = impl_.get();
  poller->Add(fd, POLLIN, [impl](short) { impl->Accept(); });
}

DisplayServer::~DisplayServer() = default;

void DisplayServer::Publish(bool changed) {
  const auto now = std::chrono::steady_clock::now();
  if (!changed && now - impl_->last_publish < std::chrono::seconds(1)) return;
  bool any = false;
  for (const auto& [fd, client] : impl_->clients) any = any || client.events;
  if (!any) return;
  impl_->last_publish = now;
  const std::string event = "data: " + impl_->state() + "\n\n";
  std::vector<int> streams;
  for (auto& [fd, client] : impl_->clients) {
    if (!client.events) continue;
    client.pending += event;
    streams.push_back(fd);
  }
  for (const int fd : streams) impl_->Flush(fd);
}

int DisplayServer::port() const { return impl_->port; }

int DisplayServer::clients() const { return static_cast<int>(impl_->clients.size()); }

}  // namespace moorsim::monitor
