#include "monitor/feeds.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <utility>

#include "core/error.h"
#include "monitor/nmea.h"

namespace moorsim::monitor {

double UnixNow() {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count();
  return FromMicroseconds(us);
}

sockaddr_in ResolveIpv4(const std::string& host, int port, const std::string& what) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  addrinfo* found = nullptr;
  const int status = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
  if (status != 0 || found == nullptr) {
    throw InputError(what + ": '" + host + "' cannot be resolved: " + ::gai_strerror(status));
  }
  sockaddr_in address{};
  std::memcpy(&address, found->ai_addr, sizeof address);
  ::freeaddrinfo(found);
  return address;
}

void Poller::Add(int fd, short events, Handler handler) {
  handlers_[fd] = {events, std::move(handler)};
}

void Poller::Remove(int fd) { handlers_.erase(fd); }

bool Poller::Wait(int timeout_ms) {
  std::vector<pollfd> fds;
  fds.reserve(handlers_.size());
  for (const auto& [fd, entry] : handlers_) fds.push_back({fd, entry.first, 0});
  const int ready = ::poll(fds.data(), fds.size(), timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return false;
    throw Error(std::string("poll: ") + std::strerror(errno));
  }
  for (const pollfd& p : fds) {
    if (p.revents == 0) continue;
    // A handler may remove others (a feed closing): look each one up again.
    const auto found = handlers_.find(p.fd);
    if (found != handlers_.end()) {
      const Handler handler = found->second.second;
      handler(p.revents);
    }
  }
  return true;
}

int LineSplitter::Take(const char* data, std::size_t size,
                       const std::function<void(std::string)>& line) {
  int cut = 0;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = data[i];
    if (c == '\n' || c == '\r') {
      if (!skipping_ && !buffer_.empty()) line(std::move(buffer_));
      buffer_.clear();
      skipping_ = false;
      continue;
    }
    if (skipping_) continue;
    if (buffer_.size() >= kMaxLineBytes) {
      buffer_.clear();
      skipping_ = true;
      ++cut;
      continue;
    }
    buffer_ += c;
  }
  return cut;
}

int LineSplitter::End(const std::function<void(std::string)>& line) {
  if (!skipping_ && !buffer_.empty()) line(std::move(buffer_));
  buffer_.clear();
  skipping_ = false;
  return 0;
}

namespace {

std::string Errno(const std::string& what) { return what + ": " + std::strerror(errno); }

in_addr Ipv4(const scenarios::FeedConfig& config, const std::string& text, const char* key) {
  in_addr address{};
  if (::inet_pton(AF_INET, text.c_str(), &address) != 1) {
    throw InputError(config.where + "." + key + ": '" + text + "' is not an IPv4 address");
  }
  return address;
}

}  // namespace

/// One input. Subclasses open their descriptor, register it and feed bytes to Deliver.
class Feed {
 public:
  Feed(const scenarios::FeedConfig& config, int index, Poller* poller,
       std::function<void(FeedLine)>* sink)
      : config_(config), index_(index), poller_(poller), sink_(sink) {
    health_.name = config.name;
  }
  virtual ~Feed() { Close(); }
  /// Opens or reopens what is down when its wait is over; the next time it wants a look.
  virtual double Maintain(double /*now*/) { return kNever; }
  const FeedHealth& health() const { return health_; }

  static constexpr double kNever = 1e300;

 protected:
  void Register(int fd, short events) {
    fd_ = fd;
    poller_->Add(fd_, events, [this](short revents) { Ready(revents); });
  }
  void Close() {
    if (fd_ >= 0) {
      poller_->Remove(fd_);
      ::close(fd_);
      fd_ = -1;
    }
    health_.connected = false;
  }
  virtual void Ready(short revents) = 0;
  /// Bytes read at `stamp`; `end_of_message` ends a line there (a datagram).
  void Deliver(const char* data, std::size_t size, double stamp, bool end_of_message) {
    health_.bytes += static_cast<std::int64_t>(size);
    const auto line = [&](std::string text) {
      double when = stamp;
      if (config_.timing == scenarios::FeedTiming::kTags) {
        // The sender's time, from the line's TAG block; a line without one cannot be placed.
        std::string_view rest = text;
        NmeaTags tags;
        if (!SplitTagBlock(&rest, &tags, nullptr) || !tags.unix_time) {
          ++health_.untimed;
          return;
        }
        when = *tags.unix_time;
      }
      ++health_.lines;
      health_.last_line = stamp;
      (*sink_)(FeedLine{index_, std::move(text), when, stamp});
    };
    health_.overlong += splitter_.Take(data, size, line);
    if (end_of_message) health_.overlong += splitter_.End(line);
  }

  scenarios::FeedConfig config_;
  int index_;
  Poller* poller_;
  std::function<void(FeedLine)>* sink_;
  int fd_ = -1;
  FeedHealth health_;
  LineSplitter splitter_;
};

namespace {

class UdpFeed final : public Feed {
 public:
  UdpFeed(const scenarios::FeedConfig& c, int index, Poller* poller,
          std::function<void(FeedLine)>* sink)
      : Feed(c, index, poller, sink) {
    health_.kind = "udp";
    health_.endpoint = c.host + ":" + std::to_string(c.port);
    if (!c.group.empty()) health_.endpoint += " group " + c.group;
    sockaddr_in local{};
    local.sin_family = AF_INET;
    local.sin_port = htons(static_cast<std::uint16_t>(c.port));
    local.sin_addr = Ipv4(c, c.host, "udp.address");
    ip_mreq membership{};
    if (!c.group.empty()) {
      membership.imr_multiaddr = Ipv4(c, c.group, "udp.group");
      if (!IN_MULTICAST(ntohl(membership.imr_multiaddr.s_addr))) {
        throw InputError(c.where + ".udp.group: '" + c.group +
                         "' is not a multicast group (224.0.0.0 to 239.255.255.255)");
      }
      membership.imr_interface.s_addr = htonl(INADDR_ANY);
      if (!c.interface_address.empty()) {
        membership.imr_interface = Ipv4(c, c.interface_address, "udp.interface");
      }
    }
    const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) throw Error(c.where + ": " + Errno("socket"));
    const int one = 1;
    // Several programs may listen to one broadcast or multicast port.
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw InputError(c.where + ".udp: cannot listen on " + health_.endpoint + ": " + why);
    }
    if (!c.group.empty() &&
        ::setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw InputError(c.where + ".udp.group: cannot join " + c.group + ": " + why);
    }
    Register(fd, POLLIN);
    health_.connected = true;
  }

 private:
  void Ready(short /*revents*/) override {
    char datagram[65536];
    // A bounded number per wake-up, so that a flood on one port cannot starve the others.
    for (int i = 0; i < 64; ++i) {
      const ssize_t n = ::recv(fd_, datagram, sizeof datagram, 0);
      if (n < 0) {
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
          health_.problem = Errno("recv");
        }
        return;
      }
      const double stamp = UnixNow();
      std::size_t skip = 0;
      // IEC 61162-450: "UdPbC\0" and the datagram's own TAG block follow.
      if (n >= 6 && std::memcmp(datagram, "UdPbC", 6) == 0) skip = 6;
      Deliver(datagram + skip, static_cast<std::size_t>(n) - skip, stamp, true);
    }
  }
};

/// A TCP client: connects, reads, and after a refusal or a loss waits (1 s, doubling to
/// 16 s while it fails) and connects again.
class TcpFeed final : public Feed {
 public:
  TcpFeed(const scenarios::FeedConfig& c, int index, Poller* poller,
          std::function<void(FeedLine)>* sink)
      : Feed(c, index, poller, sink) {
    health_.kind = "tcp";
    health_.endpoint = c.host + ":" + std::to_string(c.port);
    server_ = ResolveIpv4(c.host, c.port, c.where + ".tcp.host");
  }

  double Maintain(double now) override {
    if (fd_ >= 0) return kNever;
    if (now < retry_at_) return retry_at_;
    Connect(now);
    return fd_ >= 0 ? kNever : retry_at_;
  }

 private:
  void Connect(double now) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      Failed(now, Errno("socket"));
      return;
    }
    const int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_KEEPALIVE, &one, sizeof one);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&server_), sizeof server_) != 0 &&
        errno != EINPROGRESS) {
      const std::string why = Errno("connect");
      ::close(fd);
      Failed(now, why);
      return;
    }
    connecting_ = true;
    Register(fd, POLLOUT);
  }

  void Failed(double now, const std::string& why) {
    Close();
    connecting_ = false;
    health_.problem = why;
    retry_at_ = now + backoff_;
    backoff_ = std::min(16.0, 2.0 * backoff_);
  }

  void Ready(short revents) override {
    const double now = UnixNow();
    if (connecting_) {
      int error = 0;
      socklen_t size = sizeof error;
      ::getsockopt(fd_, SOL_SOCKET, SO_ERROR, &error, &size);
      if (error != 0 || (revents & (POLLERR | POLLHUP))) {
        Failed(now, std::string("connect: ") + std::strerror(error != 0 ? error : ECONNREFUSED));
        return;
      }
      connecting_ = false;
      const int fd = fd_;
      poller_->Remove(fd);
      Register(fd, POLLIN);
      health_.connected = true;
      health_.problem.clear();
      if (ever_connected_) ++health_.reconnects;
      ever_connected_ = true;
      backoff_ = 1.0;
      return;
    }
    char buffer[8192];
    for (int i = 0; i < 16; ++i) {
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n > 0) {
        Deliver(buffer, static_cast<std::size_t>(n), UnixNow(), false);
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
      const std::string why =
          n == 0 ? std::string("the server closed the connection") : Errno("recv");
      Deliver(nullptr, 0, now, true);  // a last line without its end
      Failed(now, why);
      return;
    }
  }

  sockaddr_in server_{};
  bool connecting_ = false;
  bool ever_connected_ = false;
  double retry_at_ = 0.0;
  double backoff_ = 1.0;
};

speed_t Speed(int baud) {
  switch (baud) {
    case 4800:
      return B4800;
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    default:
      return B230400;
  }
}

/// A serial device, or a named pipe or file read as it is written (timed on arrival): read
/// raw; reopened every 2 s while absent or after it fails (a USB adapter pulled out).
class DeviceFeed final : public Feed {
 public:
  DeviceFeed(const scenarios::FeedConfig& c, int index, Poller* poller,
             std::function<void(FeedLine)>* sink)
      : Feed(c, index, poller, sink),
        serial_(c.kind == scenarios::FeedConfig::Kind::kSerial),
        path_(serial_ ? c.device : c.path) {
    health_.kind = serial_ ? "serial" : "file";
    health_.endpoint = path_;
  }

  double Maintain(double now) override {
    if (fd_ >= 0 || ended_) return kNever;
    if (now < retry_at_) return retry_at_;
    Open(now);
    return fd_ >= 0 ? kNever : retry_at_;
  }

 private:
  void Open(double now) {
    struct stat info {};
    const bool fifo = ::stat(path_.c_str(), &info) == 0 && S_ISFIFO(info.st_mode);
    // A pipe opened for writing too never reports its end between two writers.
    const int flags = (fifo ? O_RDWR : O_RDONLY) | O_NOCTTY | O_NONBLOCK | O_CLOEXEC;
    const int fd = ::open(path_.c_str(), flags);
    if (fd < 0) {
      Failed(now, Errno(path_));
      return;
    }
    if (serial_) {
      termios tty{};
      if (::tcgetattr(fd, &tty) != 0) {
        const std::string why = Errno(path_ + ": not a serial device (tcgetattr)");
        ::close(fd);
        Failed(now, why);
        return;
      }
      ::cfmakeraw(&tty);
      ::cfsetispeed(&tty, Speed(config_.baud));
      ::cfsetospeed(&tty, Speed(config_.baud));
      tty.c_cflag &= ~static_cast<tcflag_t>(CSIZE | CSTOPB | PARENB | PARODD | CRTSCTS);
      tty.c_cflag |= CS8 | CLOCAL | CREAD;
      if (config_.parity != scenarios::SerialParity::kNone) {
        tty.c_cflag |= PARENB;
        tty.c_iflag |= INPCK;
        if (config_.parity == scenarios::SerialParity::kOdd) tty.c_cflag |= PARODD;
      }
      if (::tcsetattr(fd, TCSANOW, &tty) != 0) {
        const std::string why = Errno(path_ + ": tcsetattr");
        ::close(fd);
        Failed(now, why);
        return;
      }
    }
    regular_ = S_ISREG(info.st_mode);
    Register(fd, POLLIN);
    health_.connected = true;
    health_.problem.clear();
    if (ever_open_) ++health_.reconnects;
    ever_open_ = true;
  }

  void Failed(double now, const std::string& why) {
    Close();
    health_.problem = why;
    retry_at_ = now + 2.0;
  }

  void Ready(short revents) override {
    char buffer[8192];
    for (int i = 0; i < 16; ++i) {
      const ssize_t n = ::read(fd_, buffer, sizeof buffer);
      if (n > 0) {
        Deliver(buffer, static_cast<std::size_t>(n), UnixNow(), false);
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
        if (revents & (POLLERR | POLLHUP)) Failed(UnixNow(), path_ + ": the device hung up");
        return;
      }
      Deliver(nullptr, 0, UnixNow(), true);
      if (n == 0 && regular_) {
        // A file read to its end: what it held has been read.
        Close();
        ended_ = true;
        health_.problem = "read to its end";
        return;
      }
      Failed(UnixNow(), n == 0 ? path_ + ": closed" : Errno(path_));
      return;
    }
  }

  bool serial_;
  std::string path_;
  bool regular_ = false;
  bool ended_ = false;
  bool ever_open_ = false;
  double retry_at_ = 0.0;
};

}  // namespace

Feeds::Feeds(const std::vector<scenarios::FeedConfig>& feeds, Poller* poller,
             std::function<void(FeedLine)> sink)
    : sink_(std::make_unique<std::function<void(FeedLine)>>(std::move(sink))) {
  for (std::size_t i = 0; i < feeds.size(); ++i) {
    const scenarios::FeedConfig& c = feeds[i];
    const int index = static_cast<int>(i);
    switch (c.kind) {
      case scenarios::FeedConfig::Kind::kUdp:
        feeds_.push_back(std::make_unique<UdpFeed>(c, index, poller, sink_.get()));
        break;
      case scenarios::FeedConfig::Kind::kTcp:
        feeds_.push_back(std::make_unique<TcpFeed>(c, index, poller, sink_.get()));
        break;
      case scenarios::FeedConfig::Kind::kSerial:
      case scenarios::FeedConfig::Kind::kFile:
        if (c.kind == scenarios::FeedConfig::Kind::kFile &&
            c.timing == scenarios::FeedTiming::kTags) {
          throw ContractError(c.where + ": a tagged log is replayed, not followed");
        }
        feeds_.push_back(std::make_unique<DeviceFeed>(c, index, poller, sink_.get()));
        break;
    }
  }
}

Feeds::~Feeds() = default;

double Feeds::Maintain(double now) {
  double next = Feed::kNever;
  for (const auto& feed : feeds_) next = std::min(next, feed->Maintain(now));
  return next;
}

std::vector<FeedHealth> Feeds::Health() const {
  std::vector<FeedHealth> health;
  for (const auto& feed : feeds_) health.push_back(feed->health());
  return health;
}

struct TaggedLog::State {
  std::ifstream in;
  std::string path;
};

TaggedLog::TaggedLog(const std::string& path, int feed)
    : state_(std::make_unique<State>()), feed_(feed) {
  state_->path = path;
  state_->in.open(path, std::ios::binary);
  if (!state_->in) throw InputError(path + ": cannot be read");
}

TaggedLog::~TaggedLog() = default;

bool TaggedLog::Next(FeedLine* line) {
  std::string text;
  while (std::getline(state_->in, text)) {
    while (!text.empty() && (text.back() == '\r' || text.back() == '\n')) text.pop_back();
    if (text.empty()) continue;
    if (text.size() > kMaxLineBytes) text.resize(kMaxLineBytes);
    std::string_view rest = text;
    NmeaTags tags;
    if (!SplitTagBlock(&rest, &tags, nullptr) || !tags.unix_time) {
      ++untimed_;  // no time: nothing to place it by
      continue;
    }
    last_ = *tags.unix_time;
    *line = FeedLine{feed_, std::move(text), last_, UnixNow()};
    return true;
  }
  return false;
}

}  // namespace moorsim::monitor
