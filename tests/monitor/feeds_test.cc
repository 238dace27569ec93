// The monitor's feeds (monitor/feeds.h) on real descriptors of this machine: UDP datagrams
// (a broadcast-style port shared with another listener, and a multicast group where the
// loopback carries one), a TCP server that goes away and comes back (the client connects
// again), a serial line (a pseudo-terminal set to 9600 baud, raw), a named pipe
// written by two writers in turn, and lines timed by their TAG blocks.
#include "monitor/feeds.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "monitor/nmea.h"
#include "tests/monitor/monitor_test_support.h"

namespace moorsim::monitor {
namespace {

using testing::FreePort;

// A set of feeds on their own poller, and the lines they delivered.
struct Harness {
  explicit Harness(std::vector<scenarios::FeedConfig> configs) {
    for (std::size_t i = 0; i < configs.size(); ++i) {
      if (configs[i].where.empty()) configs[i].where = "feeds[" + std::to_string(i + 1) + "]";
    }
    feeds = std::make_unique<Feeds>(configs, &poller, [this](FeedLine l) { lines.push_back(l); });
  }
  // Polls (and retries what is down) until `done` or `seconds` pass.
  bool Until(const std::function<bool()>& done, double seconds = 5.0) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      feeds->Maintain(UnixNow());
      poller.Wait(20);
      if (done()) return true;
    }
    return false;
  }
  std::vector<std::string> Texts() const {
    std::vector<std::string> texts;
    for (const FeedLine& l : lines) texts.push_back(l.text);
    return texts;
  }
  Poller poller;
  std::unique_ptr<Feeds> feeds;
  std::vector<FeedLine> lines;
};

sockaddr_in Loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}

scenarios::FeedConfig Udp(int port) {
  scenarios::FeedConfig c;
  c.name = "udp";
  c.kind = scenarios::FeedConfig::Kind::kUdp;
  c.host = "127.0.0.1";
  c.port = port;
  return c;
}

TEST(Feeds, UdpDatagramsAreSplitIntoLinesAndTwoProgramsMayListen) {
  const int port = FreePort(SOCK_DGRAM);
  Harness a({Udp(port)}), b({Udp(port)});  // SO_REUSEADDR: a second listener binds too
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  const sockaddr_in to = Loopback(port);
  // Two sentences in one datagram, the second without its line end; a 61162-450 header.
  const std::string datagram = "$GPHDT,1.0,T*00\r\n$GPHDT,2.0,T*00";
  ::sendto(s, datagram.data(), datagram.size(), 0, reinterpret_cast<const sockaddr*>(&to),
           sizeof to);
  const std::string framed = std::string("UdPbC\0", 6) + "$GPHDT,3.0,T*00\r\n";
  ::sendto(s, framed.data(), framed.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  ::close(s);
  // A unicast datagram reaches one of the listeners (broadcast and multicast reach both).
  ASSERT_TRUE(a.Until([&] { return a.lines.size() + b.lines.size() >= 3; }, 1.0) ||
              b.Until([&] { return a.lines.size() + b.lines.size() >= 3; }, 1.0));
  std::vector<std::string> all = a.Texts();
  for (const std::string& t : b.Texts()) all.push_back(t);
  EXPECT_EQ(all,
            (std::vector<std::string>{"$GPHDT,1.0,T*00", "$GPHDT,2.0,T*00", "$GPHDT,3.0,T*00"}));
}

TEST(Feeds, AMulticastGroupIsJoinedAndHeard) {
  const int port = FreePort(SOCK_DGRAM);
  scenarios::FeedConfig c = Udp(port);
  c.host = "0.0.0.0";
  c.group = "239.192.0.9";
  c.interface_address = "127.0.0.1";
  Harness h({c});
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  in_addr local{};
  local.s_addr = htonl(INADDR_LOOPBACK);
  ::setsockopt(s, IPPROTO_IP, IP_MULTICAST_IF, &local, sizeof local);
  const unsigned char loop = 1;
  ::setsockopt(s, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
  sockaddr_in to = Loopback(port);
  ::inet_pton(AF_INET, c.group.c_str(), &to.sin_addr);
  const std::string sentence = "$HEHDT,45.0,T*00\r\n";
  const auto sent = ::sendto(s, sentence.data(), sentence.size(), 0,
                             reinterpret_cast<const sockaddr*>(&to), sizeof to);
  ::close(s);
  if (sent < 0) GTEST_SKIP() << "this machine's loopback carries no multicast";
  ASSERT_TRUE(h.Until([&] { return !h.lines.empty(); }, 2.0));
  EXPECT_EQ(h.lines[0].text, "$HEHDT,45.0,T*00");
}

TEST(Feeds, ATcpClientConnectsAgainWhenItsServerComesBack) {
  const int port = FreePort(SOCK_STREAM);
  scenarios::FeedConfig c;
  c.name = "tcp";
  c.kind = scenarios::FeedConfig::Kind::kTcp;
  c.host = "127.0.0.1";
  c.port = port;
  Harness h({c});
  // No server yet: refused, said, and tried again.
  ASSERT_TRUE(h.Until([&] { return !h.feeds->Health()[0].problem.empty(); }, 3.0));
  EXPECT_FALSE(h.feeds->Health()[0].connected);
  const auto serve = [&](const std::string& text) {
    const int server = ::socket(AF_INET, SOCK_STREAM, 0);
    const int one = 1;
    ::setsockopt(server, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    const sockaddr_in at = Loopback(port);
    EXPECT_EQ(::bind(server, reinterpret_cast<const sockaddr*>(&at), sizeof at), 0);
    ::listen(server, 1);
    int client = -1;
    EXPECT_TRUE(h.Until(
        [&] {
          pollfd p = {server, POLLIN, 0};
          if (::poll(&p, 1, 0) == 1) client = ::accept(server, nullptr, nullptr);
          return client >= 0;
        },
        20.0));
    ::send(client, text.data(), text.size(), MSG_NOSIGNAL);
    ::close(client);  // the server goes away
    ::close(server);
  };
  serve("$HEHDT,1.0,T*00\r\n$HEHDT,2.0,T*00");  // the last line ends with the connection
  ASSERT_TRUE(h.Until([&] { return h.lines.size() == 2; }));
  ASSERT_TRUE(h.Until([&] { return !h.feeds->Health()[0].connected; }));
  serve("$HEHDT,3.0,T*00\r\n");
  ASSERT_TRUE(h.Until([&] { return h.lines.size() == 3; }));
  EXPECT_EQ(h.Texts(),
            (std::vector<std::string>{"$HEHDT,1.0,T*00", "$HEHDT,2.0,T*00", "$HEHDT,3.0,T*00"}));
  EXPECT_EQ(h.feeds->Health()[0].reconnects, 1);
}

TEST(Feeds, ASerialLineIsSetToItsSpeedAndParityAndRead) {
  int master = -1, slave = -1;
  char name[256];
  ASSERT_EQ(::openpty(&master, &slave, name, nullptr, nullptr), 0);
  scenarios::FeedConfig c;
  c.name = "serial";
  c.kind = scenarios::FeedConfig::Kind::kSerial;
  c.device = name;
  c.baud = 9600;
  c.parity = scenarios::SerialParity::kEven;
  Harness h({c});
  ASSERT_TRUE(h.Until([&] { return h.feeds->Health()[0].connected; }));
  termios tty{};
  ASSERT_EQ(::tcgetattr(slave, &tty), 0);
  // (A pseudo-terminal keeps the speed and the raw mode; it has no parity bit to keep.)
  EXPECT_EQ(::cfgetispeed(&tty), B9600);
  EXPECT_EQ(tty.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
  EXPECT_FALSE(tty.c_lflag & ICANON);  // raw: lines are the feed's own
  const std::string text = "$IIXDR,N,1000.0,N,LC1*00\r\n";
  ASSERT_EQ(::write(master, text.data(), text.size()), static_cast<ssize_t>(text.size()));
  ASSERT_TRUE(h.Until([&] { return !h.lines.empty(); }));
  EXPECT_EQ(h.lines[0].text, "$IIXDR,N,1000.0,N,LC1*00");
  ::close(master);
  ::close(slave);
}

TEST(Feeds, ANamedPipeIsReadAcrossItsWritersAndTaggedLinesTakeTheirTagsTime) {
  const moorsim::testing::TempDirectory dir(::testing::TempDir());
  const std::string fifo = (dir.path() / "feed").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  scenarios::FeedConfig c;
  c.name = "pipe";
  c.kind = scenarios::FeedConfig::Kind::kFile;
  c.path = fifo;
  c.timing = scenarios::FeedTiming::kArrival;  // read as another program writes it
  Harness h({c});
  ASSERT_TRUE(h.Until([&] { return h.feeds->Health()[0].connected; }));
  for (const std::string& text :
       {std::string("$HEHDT,1.0,T*00\n"), std::string("$HEHDT,2.0,T*00\n")}) {
    const int writer = ::open(fifo.c_str(), O_WRONLY);  // one writer, then another
    ASSERT_GE(writer, 0);
    ASSERT_EQ(::write(writer, text.data(), text.size()), static_cast<ssize_t>(text.size()));
    ::close(writer);
  }
  ASSERT_TRUE(h.Until([&] { return h.lines.size() == 2; }));
  EXPECT_TRUE(h.feeds->Health()[0].connected);

  // Tags: the line's time is its c:, a line without one is counted and dropped.
  const int port = FreePort(SOCK_DGRAM);
  scenarios::FeedConfig tagged = Udp(port);
  tagged.timing = scenarios::FeedTiming::kTags;
  Harness t({tagged});
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  const sockaddr_in to = Loopback(port);
  const std::string datagram =
      NmeaTagBlock(1796662649.25) + "$HEHDT,1.0,T*00\r\n$HEHDT,2.0,T*00\r\n";
  ::sendto(s, datagram.data(), datagram.size(), 0, reinterpret_cast<const sockaddr*>(&to),
           sizeof to);
  ::close(s);
  ASSERT_TRUE(t.Until([&] { return t.feeds->Health()[0].untimed == 1; }));
  ASSERT_EQ(t.lines.size(), 1u);
  EXPECT_EQ(t.lines[0].stamp, 1796662649.25);
  EXPECT_GT(t.lines[0].arrival, 1796662649.25);
}

}  // namespace
}  // namespace moorsim::monitor
