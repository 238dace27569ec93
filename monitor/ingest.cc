#include "monitor/ingest.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "monitor/nmea.h"

namespace moorsim::monitor {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

ChannelHealth Channel(std::string name) {
  ChannelHealth c;
  c.name = std::move(name);
  return c;
}

/// A fix this far from the frame's origin is not this vessel's [m].
constexpr double kMaxDistance = 100e3;
/// The largest tension or thrust component believed [N, N m].
constexpr double kMaxLoad = 1e9;

/// A CSV cell as a number, the spaces around it allowed.
std::optional<double> Number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  return NmeaNumber(text);
}

}  // namespace

Ingest::Ingest(const scenarios::MonitorConfig& config, int lines, double rate, double epoch,
               Waits waits)
    : config_(config),
      waits_(waits),
      lines_(lines),
      rate_(rate),
      epoch_(epoch),
      frame_(config.latitude, config.longitude),
      cos_grid_(std::cos(config.grid_north * kDegree)),
      sin_grid_(std::sin(config.grid_north * kDegree)),
      counts_(config.feeds.size()),
      cell_value_(config.cells.size(), kNaN),
      cell_time_(config.cells.size(), -kInfinity),
      cell_interval_(config.cells.size(), -1),
      latest_tensions_(VecX::Constant(lines, kNaN)) {
  if (!(rate > 0.0)) throw ContractError("Ingest: the sample rate must be positive");
  channels_.push_back(Channel("position"));
  channels_.push_back(Channel("heading"));
  for (std::size_t i = 0; i < config.cells.size(); ++i) {
    const scenarios::CellConfig& cell = config.cells[i];
    if (cell.line > lines) {
      throw InputError(config.source_path + ": cells[" + std::to_string(i + 1) +
                       "].line: " + std::to_string(cell.line) + " but the scenario has " +
                       std::to_string(lines) + " lines");
    }
    cell_of_transducer_[cell.transducer] = static_cast<int>(channels_.size());
    channels_.push_back(
        Channel("cell " + cell.transducer + " (line " + std::to_string(cell.line) + ")"));
  }
  if (!config.cells.empty() && static_cast<int>(config.cells.size()) != lines) {
    throw InputError(config.source_path + ": cells: " + std::to_string(config.cells.size()) +
                     " cells for " + std::to_string(lines) +
                     " lines (the detectors read a cell on every line, or none)");
  }
  if (config.thrust) channels_.push_back(Channel("thrust"));
}

bool Ingest::Claim(int channel, int feed) {
  ChannelHealth& c = channels_[static_cast<std::size_t>(channel)];
  const std::string& name = config_.feeds[static_cast<std::size_t>(feed)].name;
  if (c.feed.empty()) c.feed = name;
  // The first feed that brings a channel keeps it: two receivers are never mixed.
  return c.feed == name;
}

void Ingest::Reject(int channel, int feed, const std::string& why) {
  ChannelHealth& c = channels_[static_cast<std::size_t>(channel)];
  ++c.rejected;
  c.problem = why;
  counts_[static_cast<std::size_t>(feed)].last_fault = c.name + ": " + why;
}

void Ingest::Take(const FeedLine& line) {
  arrival_ = line.arrival;
  const double tau = line.stamp - epoch_;
  CloseBefore(tau);
  FeedCounts& counts = counts_[static_cast<std::size_t>(line.feed)];
  const scenarios::FeedConfig& feed = config_.feeds[static_cast<std::size_t>(line.feed)];
  const auto fault = [&](const std::string& kind, const std::string& detail) {
    ++counts.faults[kind];
    counts.last_fault = kind + ": " + detail;
  };

  if (feed.format != scenarios::FeedFormat::kNmea) {
    // The thrust feed's own rows.
    const int channel = static_cast<int>(channels_.size()) - 1;
    std::optional<Vec3> thrust;
    if (feed.format == scenarios::FeedFormat::kJson) {
      try {
        const nlohmann::json j = nlohmann::json::parse(line.text);
        Vec3 v;
        int i = 0;
        for (const char* key : {"surge", "sway", "yaw"}) {
          if (!j.is_object() || !j.contains(key) || !j[key].is_number()) {
            fault("bad field", std::string("no number '") + key + "'");
            return;
          }
          v(i++) = j[key].get<double>();
        }
        thrust = v;
      } catch (const nlohmann::json::exception&) {
        fault("not JSON", "a line that is not a JSON object");
        return;
      }
    } else {
      Vec3 v;
      std::string_view rest = line.text;
      int i = 0;
      for (; i < 3; ++i) {
        const std::size_t comma = rest.find(',');
        const std::optional<double> x = Number(rest.substr(0, comma));
        if (!x) break;
        v(i) = *x;
        rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
        if (comma == std::string_view::npos && i < 2) {
          i = -1;
          break;
        }
      }
      if (i != 3 || !rest.empty()) {
        if (line.text.find("surge") != std::string::npos) return;  // a header row
        fault("bad field", "not three numbers surge,sway,yaw");
        return;
      }
      thrust = v;
    }
    if (!Claim(channel, line.feed)) {
      ++counts.ignored;
      return;
    }
    ++counts.sentences;
    if (!(thrust->cwiseAbs().maxCoeff() <= kMaxLoad)) {
      Reject(channel, line.feed, "a component beyond 1e9");
      return;
    }
    ChannelHealth& c = channels_[static_cast<std::size_t>(channel)];
    ++c.readings;
    c.last = line.stamp;
    thrust_ = *thrust;
    latest_thrust_ = *thrust;
    if (InOpen(tau)) window_.thrust = true;
    if (Complete()) Close();
    return;
  }

  std::string_view text = line.text;
  NmeaTags tags;
  std::string why;
  if (!SplitTagBlock(&text, &tags, &why)) {
    fault("bad TAG block", why);
    return;
  }
  const NmeaParse parse = ParseNmea(text);
  if (!parse.sentence) {
    fault(std::string(ChoiceName(parse.fault)), parse.detail);
    return;
  }
  const NmeaSentence& s = *parse.sentence;
  if (s.type == "GGA" || s.type == "GNS" || s.type == "RMC") {
    const std::optional<NmeaFix> fix = DecodeFix(s, &why);
    if (!fix) return fault("bad field", why);
    if (!Claim(kPositionChannel, line.feed)) {
      ++counts.ignored;
      return;
    }
    ++counts.sentences;
    if (fix->quality == 0) return Reject(kPositionChannel, line.feed, s.type + ": no fix");
    const Vec3 ned = frame_.NorthEastDown(fix->latitude, fix->longitude);
    if (ned.head<2>().norm() > kMaxDistance) {
      return Reject(kPositionChannel, line.feed,
                    s.type + ": " + FormatNumber(std::round(ned.head<2>().norm())) +
                        " m from the origin (more than 100 km)");
    }
    ChannelHealth& c = channels_[kPositionChannel];
    ++c.readings;
    c.last = line.stamp;
    c.detail = s.type + " quality " + std::to_string(fix->quality);
    if (fix->satellites) c.detail += ", " + std::to_string(*fix->satellites) + " satellites";
    if (fix->hdop) c.detail += ", HDOP " + FormatNumber(*fix->hdop);
    // The scenario's axes: its north turned `grid_north` clockwise from true north.
    const Vec3 grid(cos_grid_ * ned(0) + sin_grid_ * ned(1),
                    -sin_grid_ * ned(0) + cos_grid_ * ned(1), ned(2));
    if (Start(tau) && !window_.fix) window_.fix = grid;
    const double psi = heading_.value_or(0.0);
    latest_pose_(0) =
        grid(0) - (std::cos(psi) * config_.antenna[0] - std::sin(psi) * config_.antenna[1]);
    latest_pose_(1) =
        grid(1) - (std::sin(psi) * config_.antenna[0] + std::cos(psi) * config_.antenna[1]);
  } else if (s.type == "HDT" || s.type == "THS") {
    const std::optional<NmeaHeading> heading = DecodeHeading(s, &why);
    if (!heading) return fault("bad field", why);
    if (!Claim(kHeadingChannel, line.feed)) {
      ++counts.ignored;
      return;
    }
    ++counts.sentences;
    if (heading->mode && *heading->mode == 'V') {
      return Reject(kHeadingChannel, line.feed, "THS: mode V (not valid)");
    }
    ChannelHealth& c = channels_[kHeadingChannel];
    ++c.readings;
    c.last = line.stamp;
    c.detail = heading->mode ? s.type + " mode " + std::string(1, *heading->mode) : s.type;
    const double psi = (heading->degrees - config_.grid_north) * kDegree;
    if (Start(tau) && !window_.heading) window_.heading = psi;
    latest_pose_(2) = heading_ ? *heading_ + WrapAngle(psi - *heading_) : WrapAngle(psi);
  } else if (s.type == "XDR") {
    const std::optional<std::vector<NmeaTransducer>> transducers = DecodeTransducers(s, &why);
    if (!transducers) return fault("bad field", why);
    ++counts.sentences;
    for (const NmeaTransducer& t : *transducers) {
      if (config_.thrust && !config_.thrust->transducers.empty()) {
        const auto& names = config_.thrust->transducers;
        const auto found = std::find(names.begin(), names.end(), t.name);
        if (found != names.end()) {
          const int channel = static_cast<int>(channels_.size()) - 1;
          if (config_.thrust->feed != feed.name || !Claim(channel, line.feed)) continue;
          if (!(std::abs(t.value) <= kMaxLoad)) {
            Reject(channel, line.feed, t.name + ": beyond 1e9");
            continue;
          }
          thrust_(found - names.begin()) = t.value;
          latest_thrust_ = thrust_;
          if (InOpen(tau) && found - names.begin() == 2) window_.thrust = true;
          ChannelHealth& c = channels_[static_cast<std::size_t>(channel)];
          ++c.readings;
          c.last = line.stamp;
          continue;
        }
      }
      const auto cell = cell_of_transducer_.find(t.name);
      if (cell == cell_of_transducer_.end()) continue;
      const int channel = cell->second;
      if (!Claim(channel, line.feed)) continue;
      const std::size_t k = static_cast<std::size_t>(channel - 2);
      const scenarios::CellConfig& spec = config_.cells[k];
      if (t.type != 'N' || t.units != spec.units) {
        Reject(channel, line.feed,
               "type " + std::string(1, t.type) + ", units '" + t.units + "' (expected N, '" +
                   spec.units + "')");
        continue;
      }
      const double newtons = t.value * spec.scale;
      if (!(std::abs(newtons) <= kMaxLoad)) {
        Reject(channel, line.feed, FormatNumber(newtons) + " N is beyond 1e9 N");
        continue;
      }
      ChannelHealth& c = channels_[static_cast<std::size_t>(channel)];
      ++c.readings;
      c.last = line.stamp;
      cell_value_[k] = newtons;
      cell_time_[k] = tau;
      if (InOpen(tau)) cell_interval_[k] = open_;
      latest_tensions_(spec.line - 1) = newtons;
    }
  } else if (s.type == "ZDA") {
    // Read to check it; the monitor's clock is the system's (kept by NTP or the GNSS).
    if (!DecodeClock(s, &why)) return fault("bad field", why);
    ++counts.sentences;
  } else {
    ++counts.ignored;
  }
  if (Complete()) Close();
}

bool Ingest::Complete() const {
  if (!window_.fix || !window_.heading) return false;
  if (config_.thrust && waits_.thrust && !window_.thrust) return false;
  if (!waits_.cells) return true;
  // Every cell that is not stale at the interval's start has read in it.
  const double t = static_cast<double>(open_) / rate_;
  for (std::size_t k = 0; k < cell_time_.size(); ++k) {
    if (cell_interval_[k] != open_ && cell_time_[k] >= t - config_.stale_after) return false;
  }
  return true;
}

bool Ingest::Start(double tau) {
  if (open_ < 0) {
    // The first reading of position or heading opens the first interval, its own.
    open_ = static_cast<std::int64_t>(std::floor(tau * rate_));
    while (tau >= static_cast<double>(open_ + 1) / rate_) ++open_;
    ExpectCellsFrom(static_cast<double>(open_) / rate_);
  }
  // A reading behind the open interval belongs to one closed already.
  return tau >= static_cast<double>(open_) / rate_;
}

void Ingest::Advance(double now, double wall) {
  arrival_ = wall;
  CloseBefore(now - epoch_);
}

double Ingest::NextDeadline() const {
  if (open_ < 0) return kInfinity;
  return epoch_ + static_cast<double>(open_ + 1) / rate_;
}

void Ingest::CloseBefore(double tau) {
  if (open_ < 0) return;
  while (tau >= static_cast<double>(open_ + 1) / rate_) {
    if (!active_ && !window_.fix && !window_.heading) {
      // Suspended and nothing read: jump to the interval of `tau`.
      open_ = std::max(open_ + 1, static_cast<std::int64_t>(std::floor(tau * rate_)));
      continue;
    }
    Close();
  }
}

void Ingest::Close() {
  const double t = static_cast<double>(open_) / rate_;
  const std::optional<Vec3> fix = window_.fix;
  const std::optional<double> heading = window_.heading;
  window_ = Window{};
  ++open_;

  std::optional<double> psi;
  if (heading) psi = heading_ ? *heading_ + WrapAngle(*heading - *heading_) : WrapAngle(*heading);
  if (heading) heading_ = psi;
  if (fix) last_position_ = t;
  if (heading) last_heading_ = t;

  if (!active_) {
    if (!(fix && heading)) return;
    active_ = true;
    segment_start_ = true;
  } else if (t - last_position_ > config_.max_gap || t - last_heading_ > config_.max_gap) {
    active_ = false;  // suspended: the next sample with both starts afresh
    return;
  }
  Sample sample;
  sample.index = open_ - 1;
  sample.starts_segment = segment_start_;
  sample.arrival = arrival_;
  segment_start_ = false;
  detectors::Observation& o = sample.observation;
  o.t = t;
  o.valid = {fix.has_value() && heading_.has_value(), fix.has_value() && heading_.has_value(),
             heading.has_value()};
  if (fix && heading_) {
    const double c = std::cos(*heading_), s = std::sin(*heading_);
    o.pose(0) = (*fix)(0) - (c * config_.antenna[0] - s * config_.antenna[1]);
    o.pose(1) = (*fix)(1) - (s * config_.antenna[0] + c * config_.antenna[1]);
  }
  if (heading) o.pose(2) = *psi;
  o.tau_command = thrust_;
  if (!config_.cells.empty()) {
    // Each cell's latest reading, withheld (NaN) while it is stale; none while all are.
    VecX tensions = VecX::Constant(lines_, kNaN);
    bool any = false;
    for (std::size_t k = 0; k < config_.cells.size(); ++k) {
      if (cell_time_[k] < t - config_.stale_after || !std::isfinite(cell_value_[k])) continue;
      tensions(config_.cells[k].line - 1) = cell_value_[k];
      any = true;
    }
    if (any) o.tensions = tensions;
  }
  samples_.push_back(std::move(sample));
}

void Ingest::ExpectCellsFrom(double t) {
  for (double& time : cell_time_) time = std::max(time, t);
}

void Ingest::Resume(std::int64_t k, const detectors::Observation& last) {
  // The cells' readings as the last sample held them.
  for (std::size_t c = 0; c < config_.cells.size() && last.tensions; ++c) {
    const double reading = (*last.tensions)(config_.cells[c].line - 1);
    if (std::isfinite(reading)) {
      cell_value_[c] = reading;
      cell_time_[c] = last.t;
    }
  }
  ExpectCellsFrom(static_cast<double>(k + 1) / rate_);
  open_ = k + 1;
  window_ = Window{};
  active_ = true;
  segment_start_ = true;
  last_position_ = last_heading_ = last.t;
  if (last.valid[2]) heading_ = last.pose(2);
  thrust_ = last.tau_command;
}

std::vector<Sample> Ingest::TakeSamples() {
  std::vector<Sample> taken;
  taken.swap(samples_);
  return taken;
}

}  // namespace moorsim::monitor
