#include "tools/simulation/batch.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <unordered_map>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "core/error.h"
#include "core/version.h"
#include "detectors/plugin_detector.h"
#include "scenarios/load.h"
#include "tools/output/hdf5_file.h"

namespace moorsim::simulation {
namespace {

// The thesis plant with its detectors runs at about this many times real time on each of
// the 2 busy cores of the reference machine (benchmarks/README.md): 340-350x over the
// detection campaigns' three sea states (the rough seas take more steps), 495x in the
// thesis's sea alone. The dry run's estimate takes the slower, so it errs long there.
constexpr double kEstimatedRealTimeFactor = 350.0;

std::string RunName(std::int64_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "%08lld", static_cast<long long>(index));
  return name;
}

std::string Shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string Duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lds", s);
  }
  return text;
}

double JsonNumber(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : kNaN; }

std::string ReadSmallFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path.string() + ": cannot read");
  return text.str();
}

/// An exclusive flock on DIR/campaign.lock for the batch's lifetime.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::filesystem::path& directory) {
    const std::filesystem::path path = directory / "campaign.lock";
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error(path.string() + ": cannot create the lock file");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw InputError("--out " + directory.string() +
                       ": another moorsim batch is writing this directory (" + path.string() +
                       " is locked); wait for it or choose another --out");
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd_, 0) != 0 || ::write(fd_, pid.data(), pid.size()) < 0) {
      // The pid is only informative; the lock is what matters.
    }
  }
  ~DirectoryLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
  }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

/// One updating line on stderr: runs done / total, failures, elapsed, ETA, throughput.
/// The ETA weighs runs by their simulated duration (an intact hour counts 4.5 failure runs
/// of 800 s).
class Progress {
 public:
  Progress(bool enabled, std::int64_t total, std::int64_t skipped, double pending_seconds)
      : enabled_(enabled),
        total_(total),
        skipped_(skipped),
        pending_seconds_(pending_seconds),
        tty_(::isatty(2) == 1) {}

  void Update(std::int64_t done, std::int64_t failed, double seconds_done, bool last) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - shown_).count();
    if (!last && since < (tty_ ? 0.5 : 10.0)) return;
    shown_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
    const std::string eta =
        seconds_done > 0.0
            ? Duration(elapsed * std::max(0.0, pending_seconds_ - seconds_done) / seconds_done)
            : "?";
    std::fprintf(stderr,
                 "%smoorsim batch: %lld/%lld runs, %lld failed, %s elapsed, ETA %s, %.2f runs/s%s",
                 tty_ ? "\r\033[K" : "", static_cast<long long>(skipped_ + done),
                 static_cast<long long>(total_), static_cast<long long>(failed),
                 Duration(elapsed).c_str(), eta.c_str(), rate, tty_ && !last ? "" : "\n");
    std::fflush(stderr);
  }

 private:
  bool enabled_;
  std::int64_t total_, skipped_;
  double pending_seconds_;
  bool tty_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point shown_{};
};

// ---------------------------------------------------------------------------------------
// The tables.

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string CsvValue(const nlohmann::json& j) {
  if (j.is_null()) return "";
  if (j.is_string()) return CsvField(j.get<std::string>());
  if (j.is_number_unsigned()) return std::to_string(j.get<std::uint64_t>());
  if (j.is_number_integer()) return std::to_string(j.get<std::int64_t>());
  if (j.is_number()) return Shortest(j.get<double>());
  if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
  return CsvField(j.dump());
}

bool ParsesAsNumber(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value);
  return !text.empty() && result.ec == std::errc() && result.ptr == end;
}

// The row's value of one table column ("failure_line", "dht.delay", a factor key, ...).
struct Column {
  std::string name;
  enum class Kind { kInt, kUInt, kFloat, kText, kFactor } kind;
  std::function<nlohmann::json(const nlohmann::json&)> get;
};

// A row's station_keeping entry `key`, or null (a row of an older campaign has none).
nlohmann::json StationKeepingValue(const nlohmann::json& row, const char* key) {
  const nlohmann::json kept = row.value("station_keeping", nlohmann::json::object());
  return kept.is_object() ? kept.value(key, nlohmann::json()) : nlohmann::json();
}

std::vector<Column> TableColumns(const std::vector<std::string>& factor_keys,
                                 const std::vector<std::string>& detectors) {
  using K = Column::Kind;
  std::vector<Column> c;
  const auto field = [](const char* key) {
    return [key](const nlohmann::json& row) { return row.value(key, nlohmann::json()); };
  };
  c.push_back({"run", K::kInt, field("run")});
  c.push_back({"block", K::kText, field("block")});
  c.push_back({"seed", K::kUInt, field("seed")});
  c.push_back({"status", K::kText, field("status")});
  for (const std::string& key : factor_keys) {
    c.push_back({key, K::kFactor, [key](const nlohmann::json& row) {
                   const nlohmann::json& f = row.at("factors");
                   return f.contains(key) ? f.at(key) : nlohmann::json();
                 }});
  }
  const auto failure = [](const char* key, nlohmann::json absent) {
    return [key, absent](const nlohmann::json& row) {
      const nlohmann::json& f = row.at("failure");
      return f.is_object() ? f.value(key, absent) : absent;
    };
  };
  c.push_back({"failure_line", K::kInt, failure("line", 0)});
  c.push_back({"failure_time", K::kFloat, failure("time", nlohmann::json())});
  c.push_back({"failure_mode", K::kText, failure("mode", "")});
  c.push_back({"duration", K::kFloat, field("duration")});
  c.push_back({"simulated_time", K::kFloat, field("simulated_time")});
  c.push_back({"wall_time", K::kFloat, field("wall_time")});
  // How well the heading and the thrust held (a row of an older campaign has none: NaN).
  for (const char* key : {"thrust_saturated_share", "heading_error_max_deg"}) {
    c.push_back({key, K::kFloat,
                 [key](const nlohmann::json& row) { return StationKeepingValue(row, key); }});
  }
  for (const std::string& d : detectors) {
    const auto of = [d](const char* key, nlohmann::json absent) {
      return [d, key, absent](const nlohmann::json& row) {
        const nlohmann::json& all = row.at("detectors");
        if (!all.contains(d)) return absent;
        const nlohmann::json& v = all.at(d).value(key, absent);
        return v.is_null() ? absent : v;
      };
    };
    c.push_back({d + ".alarm_time", K::kFloat, of("alarm_time", nlohmann::json())});
    c.push_back({d + ".isolated_line", K::kInt, of("isolated_line", 0)});
    c.push_back({d + ".delay", K::kFloat, of("delay", nlohmann::json())});
    c.push_back({d + ".false_alarms", K::kInt, of("false_alarms", 0)});
    c.push_back({d + ".max_before_failure", K::kFloat, of("max_before_failure", nlohmann::json())});
    c.push_back({d + ".isolation_delay", K::kFloat, of("isolation_delay", nlohmann::json())});
    c.push_back({d + ".final_line", K::kInt, of("final_line", 0)});
    c.push_back({d + ".alarm_seconds_before_failure", K::kFloat,
                 of("alarm_seconds_before_failure", nlohmann::json())});
  }
  c.push_back({"error", K::kText, field("error")});
  c.push_back({"command", K::kText, field("command")});
  return c;
}

void WriteCsv(const std::filesystem::path& path, const std::vector<Column>& columns,
              const std::vector<nlohmann::json>& rows) {
  std::string text;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) text += ',';
    text += CsvField(columns[i].name);
  }
  text += "\n";
  for (const nlohmann::json& row : rows) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (i > 0) text += ',';
      text += CsvValue(columns[i].get(row));
    }
    text += "\n";
  }
  WriteFileAtomically(path, text);
}

void WriteHdf5(const std::filesystem::path& path, const std::vector<Column>& columns,
               const std::vector<nlohmann::json>& rows, const std::vector<std::string>& detectors,
               const std::map<std::string, std::string>& attributes, std::uint64_t campaign_seed,
               std::int64_t num_lines) {
  const std::filesystem::path partial = path.string() + ".partial";
  {
    output::Hdf5File file(partial.string());
    for (const auto& [name, value] : attributes) file.SetAttribute("/", name, value);
    file.SetAttribute("/", "campaign_seed", campaign_seed);
    file.SetAttribute("/", "num_lines", num_lines);
    file.CreateGroup("/runs");
    const std::size_t n = rows.size();
    for (const Column& column : columns) {
      const std::string dataset = "/runs/" + column.name;
      using K = Column::Kind;
      K kind = column.kind;
      if (kind == K::kFactor) {  // numbers when every value is one, else text
        kind = K::kFloat;
        double ignored = 0.0;
        for (const nlohmann::json& row : rows) {
          const nlohmann::json v = column.get(row);
          if (v.is_string() && !ParsesAsNumber(v.get<std::string>(), ignored)) kind = K::kText;
        }
      }
      switch (kind) {
        case K::kInt: {
          std::vector<std::int64_t> v;
          for (const nlohmann::json& row : rows) {
            const nlohmann::json x = column.get(row);
            v.push_back(x.is_number() ? x.get<std::int64_t>() : 0);
          }
          file.WriteDataset(dataset, {n}, std::span<const std::int64_t>(v));
          break;
        }
        case K::kUInt: {
          std::vector<std::uint64_t> v;
          for (const nlohmann::json& row : rows) v.push_back(column.get(row).get<std::uint64_t>());
          file.WriteDataset(dataset, {n}, std::span<const std::uint64_t>(v));
          break;
        }
        case K::kFloat: {
          std::vector<double> v;
          for (const nlohmann::json& row : rows) {
            const nlohmann::json x = column.get(row);
            double value = kNaN;
            if (x.is_number()) value = x.get<double>();
            if (x.is_string()) ParsesAsNumber(x.get<std::string>(), value);
            v.push_back(value);
          }
          file.WriteDataset(dataset, {n}, std::span<const double>(v));
          break;
        }
        case K::kText:
        case K::kFactor: {
          std::vector<std::string> v;
          for (const nlohmann::json& row : rows) {
            const nlohmann::json x = column.get(row);
            v.push_back(x.is_string() ? x.get<std::string>() : x.is_null() ? "" : x.dump());
          }
          file.WriteDataset(dataset, v);
          break;
        }
      }
    }
    // Per detector: the ROC record, one row per run.
    for (const std::string& d : detectors) {
      const std::string group = "/detectors/" + d;
      file.CreateGroup(group);
      std::vector<double> thresholds;
      std::string type, description;
      double threshold = kNaN;
      for (const nlohmann::json& row : rows) {
        const nlohmann::json& all = row.at("detectors");
        if (!all.contains(d)) continue;
        const nlohmann::json& e = all.at(d);
        type = e.value("type", "");
        threshold = JsonNumber(e.value("threshold", nlohmann::json()));
        if (e.contains("thresholds")) thresholds = e.at("thresholds").get<std::vector<double>>();
        break;
      }
      description = StatisticOf(type).description;
      const std::size_t g = thresholds.size();
      std::vector<std::int64_t> crossings(n * g, 0);
      std::vector<double> first(n * g, kNaN);
      for (std::size_t r = 0; r < n; ++r) {
        const nlohmann::json& all = rows[r].at("detectors");
        if (!all.contains(d) || !all.at(d).contains("false_crossings")) continue;
        const nlohmann::json& e = all.at(d);
        if (e.at("false_crossings").size() != g) continue;
        for (std::size_t k = 0; k < g; ++k) {
          crossings[r * g + k] = e.at("false_crossings")[k].get<std::int64_t>();
          first[r * g + k] = JsonNumber(e.at("first_crossing")[k]);
        }
      }
      file.SetAttribute(group, "type", type);
      file.SetAttribute(group, "statistic", description);
      file.SetAttribute(group, "threshold", threshold);
      file.WriteDataset(group + "/thresholds", {g}, std::span<const double>(thresholds));
      file.WriteDataset(group + "/false_crossings", {n, g},
                        std::span<const std::int64_t>(crossings));
      file.WriteDataset(group + "/first_crossing", {n, g}, std::span<const double>(first));
    }
    file.Close();
  }
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) throw Error(path.string() + ": rename failed: " + error.message());
}

std::string JoinLines(const std::vector<std::string>& items) {
  std::string joined;
  for (const std::string& s : items) joined += (joined.empty() ? "" : "\n") + s;
  return joined;
}

// What --merge needs to know of the campaign without its scenario file at hand.
nlohmann::json CampaignMeta(const PreparedCampaign& p) {
  const scenarios::Campaign& c = p.campaign;
  nlohmann::json meta = {
      {"name", c.name}, {"path", c.source_path},     {"scenario", c.scenario_path},
      {"seed", c.seed}, {"factors", c.FactorKeys()}, {"runs", c.NumRuns()}};
  std::vector<std::shared_ptr<const detectors::PluginLibrary>> used;
  for (const std::string& path : p.plugin_paths)
    used.push_back(detectors::PluginLibrary::Load(path));
  if (nlohmann::json plugins = PluginsSummary(used); !plugins.empty()) {
    meta["plugins"] = plugins;
  }
  return meta;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Detector statistics.

DetectorStatistic StatisticOf(const std::string& type) {
  if (type == "dht") {
    return {"largest posterior probability of a failure hypothesis, max_k>=1 h_k",
            {0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.998, 0.999, 0.9995, 0.9999,
             0.99999, 0.999999}};
  }
  if (type == "mle") {
    return {"lead of the best failure hypothesis over intact, max_k>=1 (J_0 - J_k) [nats]",
            {0, 1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40, 50, 75, 100, 150}};
  }
  if (type == "glr") {
    return {"GLR mean-change statistic g (chi-square scaled)",
            {10, 12,  15,  18,  22,  27,  33,  39,  47,  56,  68,
             82, 100, 120, 150, 180, 220, 270, 330, 390, 470, 560}};
  }
  return {"", {}};
}

double StatisticValue(const std::string& type, const std::vector<double>& score) {
  if (score.size() < 2) return kNaN;
  double best = -std::numeric_limits<double>::infinity();
  if (type == "dht") {
    for (std::size_t k = 1; k < score.size(); ++k) best = std::max(best, score[k]);
    return best;
  }
  if (type == "mle") {
    for (std::size_t k = 1; k < score.size(); ++k) best = std::max(best, score[0] - score[k]);
    return best;
  }
  if (type == "glr") return score[0];
  return kNaN;
}

StatisticTrace::StatisticTrace(std::string type, double failure_time)
    : type_(std::move(type)),
      failure_time_(failure_time),
      thresholds_(StatisticOf(type_).thresholds),
      false_crossings_(thresholds_.size(), 0),
      first_crossing_(thresholds_.size(), kNaN) {}

void StatisticTrace::Add(double t, const std::vector<double>& score) {
  const double x = StatisticValue(type_, score);
  if (!std::isfinite(x)) return;
  const bool before = !(t >= failure_time_);  // NaN failure time: the whole run
  for (std::size_t k = 0; k < thresholds_.size(); ++k) {
    const double g = thresholds_[k];
    if (before) {
      if (x >= g && !(previous_ >= g)) ++false_crossings_[k];
    } else if (x >= g && std::isnan(first_crossing_[k])) {
      first_crossing_[k] = t;
    }
  }
  if (before) max_before_ = std::isnan(max_before_) ? x : std::max(max_before_, x);
  previous_ = x;
}

nlohmann::json StatisticTrace::ToJson() const {
  nlohmann::json first = nlohmann::json::array();
  for (const double t : first_crossing_) {
    first.push_back(std::isnan(t) ? nlohmann::json(nullptr) : nlohmann::json(t));
  }
  return {{"max_before_failure",
           std::isnan(max_before_) ? nlohmann::json(nullptr) : nlohmann::json(max_before_)},
          {"thresholds", thresholds_},
          {"false_crossings", false_crossings_},
          {"first_crossing", first}};
}

// ---------------------------------------------------------------------------------------
// Preparing and describing.

namespace {

// Loads the scenario of `run` (with its overrides), builds its detectors once per detector
// configuration (`checked`) and notes its plugins; the truth the run's row records.
PreparedCampaign::Truth LoadTruth(PreparedCampaign& p, const scenarios::CampaignRun& run,
                                  std::set<std::string>& checked) {
  const scenarios::Campaign& c = p.campaign;
  const scenarios::CampaignBlock& block = c.blocks[static_cast<std::size_t>(run.block)];
  const auto where = [&](const std::string& what) {
    std::string factors;
    for (const auto& [key, value] : run.factors) {
      factors += (factors.empty() ? "" : ", ") + key + "=" + value;
    }
    const scenarios::SourceMark m = block.mark;
    return c.source_path +
           (m.line > 0 ? ":" + std::to_string(m.line) + ":" + std::to_string(m.column)
                       : std::string()) +
           ": blocks." + block.name + ": run " + std::to_string(run.index) +
           (factors.empty() ? "" : " (" + factors + ")") + ": " + what;
  };
  try {
    const scenarios::Scenario s = scenarios::LoadScenario(c.scenario_path, run.overrides);
    if (!s.vessel)
      throw InputError(s.source_path +
                       ": a campaign runs `moorsim run`, which needs a vessel section");
    std::string key;
    for (const scenarios::DetectorEntry& d : s.detectors) {
      key += d.type + "/" + d.label + "/";
      for (const auto& [name, value] : d.parameters) key += name + "=" + Shortest(value) + ",";
      key += ";";
    }
    for (const std::string& o : run.overrides) {
      if (o.rfind("detection", 0) == 0 || o.rfind("detectors", 0) == 0 ||
          o.rfind("mooring", 0) == 0 || o.rfind("vessel", 0) == 0) {
        key += o + ";";
      }
    }
    if (checked.insert(key).second) CheckDetectors(s);
    for (const scenarios::DetectorEntry& d : s.detectors) {
      if (!d.plugin.empty() && std::find(p.plugin_paths.begin(), p.plugin_paths.end(), d.plugin) ==
                                   p.plugin_paths.end()) {
        p.plugin_paths.push_back(d.plugin);
      }
    }
    PreparedCampaign::Truth t;
    if (s.failure.line > 0) {
      t.failure_line = s.failure.line;
      t.failure_time = s.failure.time;
      t.failure_mode = s.failure.mode;
    }
    t.duration = s.simulation.duration;
    t.num_lines = static_cast<int>(s.mooring.lines.size());
    for (const scenarios::DetectorEntry& d : s.detectors) {
      t.detectors.emplace_back(d.label.empty() ? d.type : d.label, d.type);
    }
    return t;
  } catch (const InputError& e) {
    throw InputError(where(e.what()));
  }
}

}  // namespace

PreparedCampaign PrepareCampaign(const std::string& campaign_path,
                                 const std::function<int()>& stop_requested, bool progress) {
  PreparedCampaign p;
  p.campaign = scenarios::LoadCampaign(campaign_path);
  const scenarios::Campaign& c = p.campaign;
  const std::int64_t n = c.NumRuns();
  p.runs.reserve(static_cast<std::size_t>(n));
  p.truth_of.reserve(static_cast<std::size_t>(n));
  // Each configuration's truth, by its overrides but the seed (the last one).
  std::unordered_map<std::string, std::uint32_t> loaded;
  // Detector configurations already built once (by the scenario's detector sections).
  std::set<std::string> checked;
  const auto start = std::chrono::steady_clock::now();
  auto shown = start;
  const bool tty = ::isatty(2) == 1;
  for (std::int64_t i = 0; i < n; ++i) {
    if (const int signal = stop_requested ? stop_requested() : 0; signal != 0) {
      throw PreparationStopped(signal);
    }
    if (progress && i % 1024 == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (now - start > std::chrono::seconds(1) &&
          now - shown > std::chrono::milliseconds(tty ? 500 : 10'000)) {
        shown = now;
        std::fprintf(stderr, "%smoorsim batch: preparing %lld/%lld runs (%zu configurations)%s",
                     tty ? "\r\033[K" : "", static_cast<long long>(i), static_cast<long long>(n),
                     p.truths.size(), tty ? "" : "\n");
        std::fflush(stderr);
      }
    }
    scenarios::CampaignRun run = scenarios::MakeCampaignRun(c, i);
    std::string configuration;
    for (std::size_t k = 0; k + 1 < run.overrides.size(); ++k) {
      configuration += run.overrides[k] + "\n";
    }
    const auto [known, first] =
        loaded.try_emplace(std::move(configuration), static_cast<std::uint32_t>(p.truths.size()));
    if (first) p.truths.push_back(LoadTruth(p, run, checked));
    p.truth_of.push_back(known->second);
    p.simulated_seconds += p.truths[known->second].duration;
    p.runs.push_back(std::move(run));
  }
  if (progress && std::chrono::steady_clock::now() - start > std::chrono::seconds(1)) {
    std::fprintf(stderr, "%smoorsim batch: prepared %lld runs (%zu configurations)\n",
                 tty ? "\r\033[K" : "", static_cast<long long>(n), p.truths.size());
  }
  return p;
}

std::string DescribeCampaign(const PreparedCampaign& p, int threads) {
  const scenarios::Campaign& c = p.campaign;
  std::ostringstream out;
  out << "campaign " << c.name << " (" << c.source_path << "): " << p.runs.size() << " runs of "
      << c.scenario_path << ", campaign seed " << c.seed << "\n";
  for (const scenarios::CampaignBlock& b : c.blocks) {
    out << "  block " << b.name << ": " << b.Points() << " points x " << b.SeedsPerPoint()
        << " seeds = " << b.Points() * b.SeedsPerPoint() << " runs\n";
  }
  out << "run\tblock\tseed\tfailure\tduration\tfactors\n";
  for (std::size_t i = 0; i < p.runs.size(); ++i) {
    const scenarios::CampaignRun& r = p.runs[i];
    const PreparedCampaign::Truth& t = p.TruthOf(static_cast<std::int64_t>(i));
    out << r.index << "\t" << c.blocks[static_cast<std::size_t>(r.block)].name << "\t" << r.seed
        << "\t"
        << (t.failure_line > 0 ? "line " + std::to_string(t.failure_line) + " at " +
                                     Shortest(t.failure_time) + " s"
                               : std::string("none"))
        << "\t" << Shortest(t.duration) << " s\t";
    for (std::size_t k = 0; k < r.factors.size(); ++k) {
      out << (k ? " " : "") << r.factors[k].first << "=" << r.factors[k].second;
    }
    out << "\n";
  }
  const int n = std::max(1, threads);
  const double wall = p.simulated_seconds / kEstimatedRealTimeFactor / n;
  out << "total " << Shortest(p.simulated_seconds) << " simulated s; estimated wall time "
      << Duration(wall) << " on " << n << " thread" << (n > 1 ? "s" : "") << " (at about "
      << Shortest(kEstimatedRealTimeFactor)
      << "x real time per thread, the thesis plant with its detectors)\n";
  return out.str();
}

// ---------------------------------------------------------------------------------------
// Rows and tables.

nlohmann::json MakeRow(const PreparedCampaign& p, const scenarios::CampaignRun& run,
                       const RunResult& result, const std::vector<StatisticTrace>& traces,
                       const std::string& out_dir) {
  const scenarios::Campaign& c = p.campaign;
  const PreparedCampaign::Truth& t = p.TruthOf(run.index);
  nlohmann::json row;
  row["run"] = run.index;
  row["block"] = c.blocks[static_cast<std::size_t>(run.block)].name;
  row["seed"] = run.seed;
  nlohmann::json factors = nlohmann::json::object();
  for (const auto& [key, value] : run.factors) factors[key] = value;
  row["factors"] = factors;
  row["status"] = StatusName(result.status);
  row["error"] = result.message;
  // The row's own command needs the --plugin libraries too.
  std::string command = run.Command(c, out_dir);
  for (const auto& library : detectors::RegisteredPluginLibraries()) {
    command += " --plugin " + scenarios::ShellQuote(library->path());
  }
  row["command"] = command;
  if (t.failure_line > 0) {
    row["failure"] = {{"line", t.failure_line}, {"time", t.failure_time}, {"mode", t.failure_mode}};
  } else {
    row["failure"] = nullptr;
  }
  row["lines"] = t.num_lines;
  row["duration"] = t.duration;
  row["simulated_time"] = result.simulated_time;
  row["wall_time"] = result.summary.value("wall_time", 0.0);
  const nlohmann::json none = nlohmann::json::object();
  const nlohmann::json& summary_detectors =
      result.summary.contains("detectors") ? result.summary.at("detectors") : none;
  nlohmann::json detectors = nlohmann::json::object();
  for (std::size_t i = 0; i < t.detectors.size(); ++i) {
    const auto& [label, type] = t.detectors[i];
    nlohmann::json d =
        summary_detectors.contains(label) ? summary_detectors.at(label) : nlohmann::json::object();
    d["type"] = type;
    for (const char* key : {"alarm_time", "isolated_line", "delay"}) {
      if (!d.contains(key)) d[key] = nullptr;
    }
    if (!d.contains("false_alarms")) d["false_alarms"] = 0;
    if (i < traces.size()) d.update(traces[i].ToJson());
    detectors[label] = d;
  }
  row["detectors"] = detectors;
  row["integrator"] = result.summary.value("integrator", nlohmann::json::object());
  row["station_keeping"] = result.summary.value("station_keeping", nlohmann::json::object());
  return row;
}

std::vector<nlohmann::json> ReadRows(const std::filesystem::path& directory) {
  std::vector<nlohmann::json> rows;
  const std::filesystem::path dir = directory / "rows";
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) return rows;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    try {
      nlohmann::json row = nlohmann::json::parse(ReadSmallFile(entry.path()));
      if (row.contains("run") && row.contains("status")) rows.push_back(std::move(row));
    } catch (const std::exception&) {
      // Unreadable: the run is done again.
    }
  }
  return rows;
}

void WriteCampaignTables(const std::filesystem::path& directory, const std::string& campaign_text,
                         const std::string& campaign_name, const std::string& campaign_path,
                         std::uint64_t campaign_seed, const std::vector<std::string>& factor_keys,
                         std::vector<nlohmann::json> rows, const std::string& command_line) {
  std::sort(rows.begin(), rows.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
    return a.at("run").get<std::int64_t>() < b.at("run").get<std::int64_t>();
  });
  std::vector<std::string> detectors;
  std::int64_t num_lines = 0;
  for (const nlohmann::json& row : rows) {
    for (const auto& [label, value] : row.at("detectors").items()) {
      if (std::find(detectors.begin(), detectors.end(), label) == detectors.end()) {
        detectors.push_back(label);
      }
    }
    num_lines = std::max<std::int64_t>(num_lines, row.value("lines", 0));
  }
  const std::vector<Column> columns = TableColumns(factor_keys, detectors);
  WriteCsv(directory / "runs.csv", columns, rows);
  const std::map<std::string, std::string> attributes = {
      {"campaign", campaign_text},        {"campaign_name", campaign_name},
      {"campaign_path", campaign_path},   {"version", moorsim::kVersion},
      {"command_line", command_line},     {"factors", JoinLines(factor_keys)},
      {"detectors", JoinLines(detectors)}};
  WriteHdf5(directory / "campaign.h5", columns, rows, detectors, attributes, campaign_seed,
            num_lines);
}

// ---------------------------------------------------------------------------------------
// The batch.

namespace {

/// The runs of this process (rank 0, or the only process): the pending list, and every row
/// written to DIR/rows as it arrives, from this process's threads or another rank's.
class LocalRunSource final : public RunSource {
 public:
  LocalRunSource(const PreparedCampaign& campaign, std::vector<std::int64_t> pending,
                 std::filesystem::path rows, Progress& progress)
      : campaign_(campaign),
        pending_(std::move(pending)),
        rows_(std::move(rows)),
        progress_(progress) {}

  std::optional<std::int64_t> Next() override {
    const std::size_t k = next_.fetch_add(1);
    if (k >= pending_.size()) return std::nullopt;
    return pending_[k];
  }
  void Deliver(std::int64_t run, const std::string& row, bool ok) override {
    WriteFileAtomically(rows_ / (RunName(run) + ".json"), row);
    const std::lock_guard<std::mutex> guard(mutex_);
    ++done_;
    if (!ok) ++failed_;
    seconds_done_ += campaign_.TruthOf(run).duration;
    progress_.Update(done_, failed_, seconds_done_, false);
  }
  std::int64_t done() const { return done_; }
  std::int64_t failed() const { return failed_; }
  double seconds_done() const { return seconds_done_; }

 private:
  const PreparedCampaign& campaign_;
  std::vector<std::int64_t> pending_;
  std::filesystem::path rows_;
  Progress& progress_;
  std::atomic<std::size_t> next_{0};
  std::mutex mutex_;
  std::int64_t done_ = 0, failed_ = 0;
  double seconds_done_ = 0.0;
};

/// Runs from `source` on `threads` OpenMP threads until it has none left or `stop` says
/// so. Returns the first exception's message (empty if none); an exception stops all.
std::string RunWorkers(const PreparedCampaign& p, const BatchOptions& o,
                       const std::filesystem::path& directory, RunSource& source, int threads,
                       std::atomic<int>& stop_signal, const std::function<int()>& stop) {
  std::mutex mutex;
  std::string first_error;
#pragma omp parallel num_threads(threads)
  {
    while (stop() == 0) {
      try {
        const std::optional<std::int64_t> next = source.Next();
        if (!next) break;
        const scenarios::CampaignRun& run = p.runs[static_cast<std::size_t>(*next)];
        const PreparedCampaign::Truth& truth = p.TruthOf(run.index);
        std::vector<StatisticTrace> traces;
        for (const auto& detector : truth.detectors) {
          traces.emplace_back(detector.second, truth.failure_line > 0 ? truth.failure_time : kNaN);
        }
        RunRequest request;
        request.scenario_path = p.campaign.scenario_path;
        request.overrides = run.overrides;
        request.write_files = o.keep_runs;
        request.out = directory / "runs" / RunName(run.index);
        request.stop_requested = stop;
        if (o.run_timeout > 0.0) {
          request.deadline = std::chrono::steady_clock::now() +
                             std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(o.run_timeout));
        }
        request.on_row = [&traces](const Sample& s) {
          for (std::size_t i = 0; i < traces.size() && i < s.detectors.size(); ++i) {
            traces[i].Add(s.time, s.detectors[i].score);
          }
        };
        const RunResult r = RunScenario(request);
        if (r.status == RunStatus::kInterrupted) continue;  // no row: done again on resume
        source.Deliver(run.index, MakeRow(p, run, r, traces, "").dump() + "\n",
                       r.status == RunStatus::kOk);
      } catch (const std::exception& e) {
        const std::lock_guard<std::mutex> guard(mutex);
        if (first_error.empty()) first_error = e.what();
        stop_signal.store(-1);
      }
    }
  }
  return first_error;
}

}  // namespace

int DefaultThreads() { return std::max(1, omp_get_num_procs()); }

BatchResult RunBatch(const BatchOptions& o) noexcept {
  BatchResult result;
  const MpiSession& mpi = o.mpi;
  const bool coordinator = mpi.rank == 0;
  // Until rank 0 has said go, the other ranks wait for its decision: every early return of
  // rank 0 must broadcast one.
  bool decided = false;
  const auto decide = [&](int code) {
    if (!decided) {
      decided = true;
      return BroadcastDecision(mpi, code);
    }
    return code;
  };
  try {
    if (o.shard_count < 1 || o.shard_index < 0 || o.shard_index >= o.shard_count) {
      throw InputError("--shard " + std::to_string(o.shard_index + 1) + "/" +
                       std::to_string(o.shard_count) + ": expected K/N with 1 <= K <= N");
    }
    if (!(o.run_timeout >= 0.0) || !std::isfinite(o.run_timeout)) {
      throw InputError("--run-timeout " + Shortest(o.run_timeout) + ": must be >= 0 seconds");
    }
    std::atomic<int> stop_signal{0};
    const std::function<int()> stop = [&]() -> int {
      if (stop_signal.load() != 0) return stop_signal.load();
      if (o.stop_requested) {
        const int s = o.stop_requested();
        if (s != 0) stop_signal.store(s);
        return s;
      }
      return 0;
    };
    // 1. Everything checked before the first run (on every rank: they all need the runs).
    const PreparedCampaign p = PrepareCampaign(o.campaign_path, stop, o.progress);
    const scenarios::Campaign& c = p.campaign;
    result.directory = o.out.empty() ? std::filesystem::path("out") / c.name : o.out;
    const int threads = o.threads > 0 ? o.threads : DefaultThreads();

    if (!coordinator) {
      // A worker rank: runs from rank 0, rows to rank 0; nothing of the campaign on disk.
      if (const int go = decide(0); go != 0) {
        result.exit_code = go;
        return result;
      }
      std::unique_ptr<RunSource> remote = RemoteRunSource(mpi);
      const std::string error =
          RunWorkers(p, o, result.directory, *remote, threads, stop_signal, stop);
      NotifyFinished(mpi);
      if (!error.empty()) throw Error(error);
      if (stop_signal.load() > 0) result.exit_code = 128 + stop_signal.load();
      return result;
    }

    // 2. Rank 0 (or the only process) owns the directory.
    std::error_code error;
    std::filesystem::create_directories(result.directory / "rows", error);
    if (error) {
      throw InputError("--out " + result.directory.string() +
                       ": cannot create the directory: " + error.message());
    }
    const DirectoryLock lock(result.directory);
    const std::filesystem::path recorded = result.directory / "campaign.yaml";
    if (std::filesystem::exists(recorded, error)) {
      if (ReadSmallFile(recorded) != c.text) {
        throw InputError("--out " + result.directory.string() +
                         ": holds the results of another campaign (its campaign.yaml differs); "
                         "choose another --out or remove the directory");
      }
    } else {
      WriteFileAtomically(recorded, c.text);
    }
    WriteFileAtomically(result.directory / "campaign.json", CampaignMeta(p).dump(2) + "\n");

    // 3. What is left to do in this shard.
    std::set<std::int64_t> finished;
    for (const nlohmann::json& row : ReadRows(result.directory)) {
      finished.insert(row.at("run").get<std::int64_t>());
    }
    std::vector<std::int64_t> pending;
    for (const scenarios::CampaignRun& run : p.runs) {
      if (run.index % o.shard_count != o.shard_index) continue;
      ++result.runs;
      if (finished.count(run.index)) {
        ++result.skipped;
      } else {
        pending.push_back(run.index);
      }
    }

    // 4. The runs: this process's threads, and the other ranks through the service thread.
    // Each run owns everything it builds; shared are the prepared campaign (read only),
    // the next index, the counters and the rows directory.
    decide(0);
    double pending_seconds = 0.0;
    for (const std::int64_t k : pending) pending_seconds += p.TruthOf(k).duration;
    Progress progress(o.progress, result.runs, result.skipped, pending_seconds);
    LocalRunSource local(p, std::move(pending), result.directory / "rows", progress);
    std::string service_error;
    std::thread service;
    if (mpi.size > 1) {
      service = std::thread([&] {
        try {
          ServeRemoteWorkers(mpi, local, stop);
        } catch (const std::exception& e) {
          service_error = e.what();
        }
      });
    }
    std::string first_error = RunWorkers(p, o, result.directory, local, threads, stop_signal, stop);
    if (service.joinable()) service.join();
    if (first_error.empty()) first_error = service_error;
    result.done = local.done();
    result.failed = local.failed();
    progress.Update(result.done, result.failed, local.seconds_done(), true);

    // 5. The tables, from every row there is (this batch's and earlier ones').
    const std::vector<nlohmann::json> rows = ReadRows(result.directory);
    WriteCampaignTables(result.directory, c.text, c.name, c.source_path, c.seed, c.FactorKeys(),
                        rows, o.command_line);
    for (const nlohmann::json& row : rows) {
      const nlohmann::json error = StationKeepingValue(row, "heading_error_max_deg");
      result.heading_lost += error.is_number() && error.get<double>() > kHeadingLostDeg ? 1 : 0;
    }
    if (!first_error.empty()) throw Error(first_error);
    const int signal = stop_signal.load();
    if (signal > 0) {
      result.exit_code = 128 + signal;
      result.message = "stopped by signal " + std::to_string(signal) + " after " +
                       std::to_string(result.done) + " runs; the same command resumes";
    } else if (result.failed > 0) {
      result.exit_code = 1;
      result.message = std::to_string(result.failed) + " of " + std::to_string(result.done) +
                       " runs did not finish ok (status and error in runs.csv)";
    }
  } catch (const PreparationStopped& e) {
    result.exit_code = 128 + e.signal();
    result.message = "stopped by signal " + std::to_string(e.signal()) +
                     " while preparing the runs; nothing was run";
  } catch (const InputError& e) {
    result.exit_code = 2;
    result.message = e.what();
  } catch (const std::exception& e) {
    result.exit_code = 1;
    result.message = e.what();
  }
  try {
    // A rank 0 that failed before "go" releases the others with its exit code; ranks that
    // failed the same way (they read the same files) take part in the same broadcast.
    decide(result.exit_code);
  } catch (const std::exception&) {
  }
  return result;
}

void MergeCampaigns(const std::vector<std::filesystem::path>& directories,
                    const std::filesystem::path& out, const std::string& command_line) {
  if (directories.empty()) throw InputError("--merge: give at least one directory");
  std::string text;
  std::map<std::int64_t, nlohmann::json> rows;
  for (const std::filesystem::path& dir : directories) {
    const std::filesystem::path recorded = dir / "campaign.yaml";
    std::error_code error;
    if (!std::filesystem::exists(recorded, error)) {
      throw InputError("--merge " + dir.string() + ": no campaign.yaml (not a batch directory)");
    }
    const std::string t = ReadSmallFile(recorded);
    if (text.empty()) text = t;
    if (t != text) {
      throw InputError("--merge " + dir.string() + ": holds another campaign than " +
                       directories.front().string());
    }
    for (nlohmann::json& row : ReadRows(dir)) {
      const std::int64_t run = row.at("run").get<std::int64_t>();
      rows.emplace(run, std::move(row));
    }
  }
  const nlohmann::json meta =
      nlohmann::json::parse(ReadSmallFile(directories.front() / "campaign.json"));
  std::error_code error;
  std::filesystem::create_directories(out / "rows", error);
  if (error) throw InputError("--out " + out.string() + ": cannot create: " + error.message());
  const DirectoryLock lock(out);
  WriteFileAtomically(out / "campaign.yaml", text);
  WriteFileAtomically(out / "campaign.json", meta.dump(2) + "\n");
  std::vector<nlohmann::json> all;
  for (auto& [run, row] : rows) {
    WriteFileAtomically(out / "rows" / (RunName(run) + ".json"), row.dump() + "\n");
    all.push_back(std::move(row));
  }
  WriteCampaignTables(out, text, meta.at("name").get<std::string>(),
                      meta.at("path").get<std::string>(), meta.at("seed").get<std::uint64_t>(),
                      meta.at("factors").get<std::vector<std::string>>(), std::move(all),
                      command_line);
}

}  // namespace moorsim::simulation
