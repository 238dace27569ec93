// What the monitor's tests share: a configuration written for a scenario of the library, and
// free UDP and TCP ports on this machine.
#pragma once

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "scenarios/monitor_config.h"
#include "tests/cli/run_cli.h"

namespace moorsim::monitor::testing {

/// The thesis case in which line 6 parts at 400 s (the detectors name it by about 430 s).
inline const std::string kLine6 = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6.yaml";

/// A port nobody listens on now (SOCK_DGRAM or SOCK_STREAM) on 127.0.0.1.
inline int FreePort(int type) {
  const int fd = ::socket(AF_INET, type, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) != 0) {
    ::close(fd);
    throw std::runtime_error("no free port");
  }
  ::close(fd);
  return ntohs(address.sin_port);
}

/// A configuration's text for `scenario` with the given feeds' lines (YAML list entries)
/// and extra top-level lines.
inline std::string ConfigText(const std::string& scenario, const std::string& feeds,
                              const std::string& extra = "") {
  return "scenario: " + scenario +
         "\n"
         "origin: {latitude_deg: 61.25, longitude_deg: 1.75, grid_north_deg: 20}\n"
         "antenna: [40, -5, -30]\n"
         "feeds:\n" +
         feeds + "store: store\nalarms: alarms.jsonl\n" + extra;
}

}  // namespace moorsim::monitor::testing
