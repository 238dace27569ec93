// The crew's display: a web page the monitor serves itself (ships are offline: every script
// and style comes from the monitor, none from elsewhere), updated live by server-sent
// events. A small HTTP/1.1 server on the monitor's Poller:
//   GET  /                 the page (index.html, app.js, style.css, built into the program)
//   GET  /api/state        the monitor's state as JSON (Monitor::State)
//   GET  /api/events       server-sent events: the state again at every change, and at least
//                          every second
//   POST /api/ack/<number> acknowledges alarm <number> (as the bridge's ACK does); the
//                          request must carry `X-Moorsim-Acknowledge: yes`, which another
//                          site's page cannot send without a CORS grant (never given)
// Each connection gets a bounded buffer: a client that stops reading is dropped, never
// waited for; a request larger than 8 kB or not HTTP is answered 400 and closed.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "monitor/feeds.h"
#include "scenarios/monitor_config.h"

namespace moorsim::monitor {

/// The page's files as built into the program: its body and content type, or nothing for
/// a name it does not have.
struct Asset {
  std::string_view body;
  std::string_view type;
};
const Asset* FindAsset(std::string_view name);

class DisplayServer {
 public:
  /// Listens on the configuration's address and port (InputError naming `display` if it
  /// cannot). `state` gives the JSON to show; `acknowledge` acknowledges an alarm by number
  /// and says whether there was one to acknowledge.
  DisplayServer(const scenarios::DisplayConfig& config, Poller* poller,
                std::function<std::string()> state, std::function<bool(int)> acknowledge);
  ~DisplayServer();
  DisplayServer(const DisplayServer&) = delete;
  DisplayServer& operator=(const DisplayServer&) = delete;

  /// Sends the state to every event stream (if `changed`, or a second has passed).
  void Publish(bool changed);
  /// The port it listens on (the configured one, or the one the system chose for 0).
  int port() const;
  int clients() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace moorsim::monitor
