#include "monitor/harness.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "monitor/feeds.h"
#include "monitor/nmea.h"

namespace moorsim::monitor {
namespace {

/// "6115.1234567" for 61.25... (degrees and minutes, 7 decimals of a minute: 0.2 mm).
std::string DegreesMinutes(double degrees, int degree_digits) {
  const double a = std::abs(degrees);
  auto whole = static_cast<long>(std::floor(a));
  long tenth_micro_minutes = std::lround((a - static_cast<double>(whole)) * 60.0 * 1e7);
  if (tenth_micro_minutes >= 600000000L) {
    tenth_micro_minutes -= 600000000L;
    ++whole;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%0*ld%02ld.%07ld", degree_digits, whole,
                tenth_micro_minutes / 10000000L, tenth_micro_minutes % 10000000L);
  return text;
}

std::string Fixed(double value, int decimals) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

int FeedNamed(const scenarios::MonitorConfig& config, const std::string& name, const char* what) {
  for (std::size_t i = 0; i < config.feeds.size(); ++i) {
    const scenarios::FeedConfig& f = config.feeds[i];
    if (name.empty() ? f.format == scenarios::FeedFormat::kNmea : f.name == name) {
      if (f.format != scenarios::FeedFormat::kNmea) {
        throw InputError(std::string("--") + what + ": feed '" + name + "' does not read NMEA");
      }
      return static_cast<int>(i);
    }
  }
  throw InputError(std::string("--") + what + ": " +
                   (name.empty() ? std::string("the configuration has no NMEA feed")
                                 : "the configuration has no feed '" + name + "'"));
}

}  // namespace

Routing RouteFeeds(const scenarios::MonitorConfig& config, const std::string& position,
                   const std::string& heading, const std::string& cells) {
  Routing r;
  r.position = FeedNamed(config, position, "position");
  r.heading = FeedNamed(config, heading, "heading");
  r.cells = FeedNamed(config, cells, "cells");
  if (config.thrust) {
    for (std::size_t i = 0; i < config.feeds.size(); ++i) {
      if (config.feeds[i].name == config.thrust->feed) r.thrust = static_cast<int>(i);
    }
  }
  return r;
}

SentenceWriter::SentenceWriter(const scenarios::MonitorConfig& config, Routing routing,
                               double cells_rate)
    : config_(config), routing_(routing), frame_(config.latitude, config.longitude) {
  if (cells_rate > 0.0) cells_clock_.emplace(cells_rate);
}

std::vector<PlayedLine> SentenceWriter::Lines(const detectors::Observation& o, double unix_time) {
  std::vector<PlayedLine> lines;
  if (o.valid[2]) heading_ = o.pose(2);
  if (o.valid[0] && o.valid[1]) {
    // The antenna where the measured pose puts it, in true north and east.
    const double c = std::cos(heading_), s = std::sin(heading_);
    const double x = o.pose(0) + c * config_.antenna[0] - s * config_.antenna[1];
    const double y = o.pose(1) + s * config_.antenna[0] + c * config_.antenna[1];
    const double g = config_.grid_north * kDegree;
    const Vec3 ned(std::cos(g) * x - std::sin(g) * y, std::sin(g) * x + std::cos(g) * y, 0.0);
    const Vec3 geodetic = frame_.LatitudeLongitudeHeight(ned);
    const std::vector<std::string> fields = {NmeaTimeOfDay(unix_time),
                                             DegreesMinutes(geodetic(0), 2),
                                             geodetic(0) >= 0.0 ? "N" : "S",
                                             DegreesMinutes(geodetic(1), 3),
                                             geodetic(1) >= 0.0 ? "E" : "W",
                                             "1",
                                             "12",
                                             "0.8",
                                             "0.0",
                                             "M",
                                             "0.0",
                                             "M",
                                             "",
                                             ""};
    lines.push_back({routing_.position, NmeaText('$', "GPGGA", fields)});
  }
  if (o.valid[2]) {
    double degrees = std::fmod(o.pose(2) / kDegree + config_.grid_north, 360.0);
    if (degrees < 0.0) degrees += 360.0;
    std::string text = Fixed(degrees, 4);
    if (text == "360.0000") text = "0.0000";
    lines.push_back({routing_.heading, NmeaText('$', "HEHDT", {text, "T"})});
  }
  if (o.tensions && (!cells_clock_ || cells_clock_->Due(o.t))) {
    for (const scenarios::CellConfig& cell : config_.cells) {
      const double reading = (*o.tensions)(cell.line - 1) / cell.scale;
      if (!std::isfinite(reading)) continue;  // a dead cell sends nothing
      lines.push_back(
          {routing_.cells,
           NmeaText('$', "IIXDR", {"N", Fixed(reading, 1), cell.units, cell.transducer})});
    }
  }
  if (routing_.thrust >= 0) {
    const scenarios::FeedConfig& feed = config_.feeds[static_cast<std::size_t>(routing_.thrust)];
    const Vec3& t = o.tau_command;
    switch (feed.format) {
      case scenarios::FeedFormat::kJson:
        lines.push_back({routing_.thrust, "{\"surge\":" + FormatNumber(t(0)) +
                                              ",\"sway\":" + FormatNumber(t(1)) +
                                              ",\"yaw\":" + FormatNumber(t(2)) + "}"});
        break;
      case scenarios::FeedFormat::kCsv:
        lines.push_back({routing_.thrust,
                         FormatNumber(t(0)) + "," + FormatNumber(t(1)) + "," + FormatNumber(t(2))});
        break;
      case scenarios::FeedFormat::kNmea: {
        std::vector<std::string> fields;
        for (int i = 0; i < 3; ++i) {
          const std::vector<std::string> one = {"N", Fixed(t(i), 1), "N",
                                                config_.thrust->transducers[i]};
          fields.insert(fields.end(), one.begin(), one.end());
        }
        lines.push_back({routing_.thrust, NmeaText('$', "IIXDR", fields)});
        break;
      }
    }
  }
  return lines;
}

/// One feed's end, as the harness serves it.
struct Player::End {
  scenarios::FeedConfig config;
  int fd = -1;               // the UDP socket, the TCP listener, the file
  sockaddr_in to{};          // UDP
  std::vector<int> clients;  // TCP
  bool log = false;

  ~End() {
    for (const int c : clients) ::close(c);
    if (fd >= 0) ::close(fd);
  }
};

namespace {

/// Where a feed's end is reached: a monitor that listens on every interface is reached on
/// this machine's loopback.
sockaddr_in Address(const std::string& host, int port, const std::string& where) {
  return ResolveIpv4(host == "0.0.0.0" ? "127.0.0.1" : host, port, where);
}

}  // namespace

Player::Player(const scenarios::MonitorConfig& config) {
  for (const scenarios::FeedConfig& c : config.feeds) {
    auto end = std::make_unique<End>();
    end->config = c;
    const int one = 1;
    switch (c.kind) {
      case scenarios::FeedConfig::Kind::kUdp: {
        end->fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
        end->to = Address(c.group.empty() ? c.host : c.group, c.port, c.where + ".udp");
        ::setsockopt(end->fd, SOL_SOCKET, SO_BROADCAST, &one, sizeof one);
        if (!c.group.empty()) {
          const unsigned char loop = 1, ttl = 1;
          ::setsockopt(end->fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
          ::setsockopt(end->fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
          in_addr local{};
          local.s_addr = htonl(INADDR_LOOPBACK);
          if (!c.interface_address.empty())
            ::inet_pton(AF_INET, c.interface_address.c_str(), &local);
          ::setsockopt(end->fd, IPPROTO_IP, IP_MULTICAST_IF, &local, sizeof local);
        }
        break;
      }
      case scenarios::FeedConfig::Kind::kTcp: {
        end->fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
        ::setsockopt(end->fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        const sockaddr_in local = Address(c.host, c.port, c.where + ".tcp");
        if (::bind(end->fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0 ||
            ::listen(end->fd, 4) != 0) {
          throw InputError(c.where + ".tcp: cannot serve " + c.host + ":" + std::to_string(c.port) +
                           ": " + std::strerror(errno));
        }
        break;
      }
      case scenarios::FeedConfig::Kind::kFile: {
        struct stat info {};
        const bool fifo = ::stat(c.path.c_str(), &info) == 0 && S_ISFIFO(info.st_mode);
        end->log = c.timing == scenarios::FeedTiming::kTags && !fifo;
        const int flags = fifo ? O_RDWR : O_WRONLY | O_CREAT | (end->log ? O_TRUNC : O_APPEND);
        end->fd = ::open(c.path.c_str(), flags | O_CLOEXEC, 0644);
        if (end->fd < 0) {
          throw InputError(c.where + ".file: " + c.path + ": " + std::strerror(errno));
        }
        break;
      }
      case scenarios::FeedConfig::Kind::kSerial:
        throw InputError(c.where +
                         ": the harness plays to UDP, TCP and files, not to a serial "
                         "line (give the monitor a copy of its configuration with "
                         "this feed on UDP)");
    }
    ends_.push_back(std::move(end));
  }
}

Player::~Player() = default;

bool Player::OnlyLogs() const {
  for (const auto& end : ends_) {
    if (!end->log) return false;
  }
  return true;
}

void Player::Send(const PlayedLine& line, double unix_time) {
  End& end = *ends_.at(static_cast<std::size_t>(line.feed));
  std::string text = line.text + "\r\n";
  if (end.config.timing == scenarios::FeedTiming::kTags) text = NmeaTagBlock(unix_time) + text;
  switch (end.config.kind) {
    case scenarios::FeedConfig::Kind::kUdp:
      ::sendto(end.fd, text.data(), text.size(), 0, reinterpret_cast<const sockaddr*>(&end.to),
               sizeof end.to);
      break;
    case scenarios::FeedConfig::Kind::kTcp:
      for (std::size_t i = 0; i < end.clients.size();) {
        if (::send(end.clients[i], text.data(), text.size(), MSG_NOSIGNAL) < 0 && errno != EAGAIN) {
          ::close(end.clients[i]);
          end.clients.erase(end.clients.begin() + static_cast<std::ptrdiff_t>(i));
          continue;
        }
        ++i;
      }
      break;
    case scenarios::FeedConfig::Kind::kFile: {
      const char* data = text.data();
      std::size_t left = text.size();
      while (left > 0) {
        const ssize_t n = ::write(end.fd, data, left);
        if (n <= 0) {
          if (errno == EINTR) continue;
          throw Error(end.config.path + ": " + std::strerror(errno));
        }
        data += n;
        left -= static_cast<std::size_t>(n);
      }
      break;
    }
    case scenarios::FeedConfig::Kind::kSerial:
      break;
  }
}

void Player::Serve(int ms) {
  std::vector<pollfd> fds;
  std::vector<End*> listening;
  for (const auto& end : ends_) {
    if (end->config.kind == scenarios::FeedConfig::Kind::kTcp) {
      fds.push_back({end->fd, POLLIN, 0});
      listening.push_back(end.get());
    }
  }
  if (fds.empty()) {
    if (ms > 0) ::poll(nullptr, 0, ms);
    return;
  }
  if (::poll(fds.data(), fds.size(), ms) <= 0) return;
  for (std::size_t i = 0; i < fds.size(); ++i) {
    if (fds[i].revents & POLLIN) {
      const int client = ::accept4(fds[i].fd, nullptr, nullptr, SOCK_CLOEXEC);
      if (client >= 0) listening[i]->clients.push_back(client);
    }
  }
}

std::vector<int> Player::Clients() const {
  std::vector<int> clients;
  for (const auto& end : ends_) {
    clients.push_back(end->config.kind == scenarios::FeedConfig::Kind::kTcp
                          ? static_cast<int>(end->clients.size())
                          : -1);
  }
  return clients;
}

}  // namespace moorsim::monitor
