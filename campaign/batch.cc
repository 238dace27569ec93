#include "campaign/batch.h"

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
#include <ostream>
#include <set>
#include <sstream>
#include <thread>
#include <unordered_map>
#include <variant>

#include "campaign/design.h"
#include "core/error.h"
#include "core/sha256.h"
#include "core/version.h"
#include "detectors/plugin_detector.h"
#include "io/csv_table.h"
#include "io/directory_lock.h"
#include "io/hdf5_file.h"
#include "runner/scenario_plant.h"
#include "scenarios/load.h"
#include "scenarios/strict_yaml.h"
#include "vessel/hydro_data.h"

namespace moorsim::simulation {

using runner::RunRequest;
using runner::RunResult;
using runner::RunStatus;
using runner::StatusName;
using runner::WriteFileAtomically;

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

void CreateDirectory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw OptionError(
        "out", " " + directory.string() + ": cannot create the directory: " + error.message());
  }
}

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

std::string CsvValue(const nlohmann::json& j) {
  if (j.is_null()) return "";
  if (j.is_string()) return output::CsvField(j.get<std::string>());
  if (j.is_number_unsigned()) return std::to_string(j.get<std::uint64_t>());
  if (j.is_number_integer()) return std::to_string(j.get<std::int64_t>());
  if (j.is_number()) return Shortest(j.get<double>());
  if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
  return output::CsvField(j.dump());
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
    // The sensors it judged faulty: "cell 3 disagrees from 412 s; GNSS jump from 930 s", ""
    // for none.
    c.push_back({d + ".sensor_faults", K::kText, [d](const nlohmann::json& row) {
                   const nlohmann::json& all = row.at("detectors");
                   std::string text;
                   if (!all.contains(d) || !all.at(d).contains("sensor_faults")) return text;
                   for (const nlohmann::json& spell : all.at(d).at("sensor_faults")) {
                     if (!text.empty()) text += "; ";
                     text += spell.at("sensor").get<std::string>();
                     if (spell.contains("fault"))
                       text += " " + spell.at("fault").get<std::string>();
                     text += " from " +
                             scenarios::strict_yaml::WithUnit(spell.at("since").get<double>(), "s");
                   }
                   return text;
                 }});
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
    text += output::CsvField(columns[i].name);
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
      if (const detectors::DetectorStatistic* statistic = detectors::StatisticOf(type)) {
        description = statistic->description;
      }
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

// The kind of CampaignIdentity::Input that is moorsim's release, not a file.
constexpr const char* kRelease = "moorsim release";

nlohmann::json IdentityJson(const CampaignIdentity& identity) {
  nlohmann::json inputs = nlohmann::json::array();
  for (const CampaignIdentity::Input& input : identity.inputs) {
    inputs.push_back({{"what", input.what}, {"path", input.path}, {"sha256", input.sha256}});
  }
  return {{"sha256", identity.sha256}, {"inputs", inputs}};
}

// DIR/campaign.json: the campaign's identity, and what --merge needs to know of the campaign
// without its scenario file at hand.
nlohmann::json CampaignMeta(const PreparedCampaign& p) {
  const scenarios::Campaign& c = p.campaign;
  nlohmann::json meta = {{"name", c.name},
                         {"path", c.source_path},
                         {"scenario", c.scenario_path},
                         {"seed", c.seed},
                         {"factors", c.FactorKeys()},
                         {"runs", c.NumRuns()},
                         {"version", moorsim::kVersion},
                         {"identity", IdentityJson(p.identity)}};
  std::vector<std::shared_ptr<const detectors::PluginLibrary>> used;
  for (const std::string& path : p.plugin_paths)
    used.push_back(detectors::PluginLibrary::Load(path));
  if (nlohmann::json plugins = PluginsSummary(used); !plugins.empty()) {
    meta["plugins"] = plugins;
  }
  return meta;
}

bool IsString(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j.at(key).is_string();
}

// DIR/campaign.json, checked for what a resume and a merge read. Throws InputError
// OptionError "<option> DIR: ..." for a directory without one, a damaged one, and one of a moorsim
// that recorded no identity.
nlohmann::json ReadCampaignRecord(const std::filesystem::path& directory,
                                  const std::string& option) {
  const std::filesystem::path path = directory / "campaign.json";
  const std::string where = " " + directory.string() + ": ";
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw OptionError(option,
                      where + "no campaign.json (not a results directory of moorsim batch)");
  }
  nlohmann::json record;
  try {
    record = nlohmann::json::parse(ReadSmallFile(path));
  } catch (const nlohmann::json::exception&) {
  }
  bool whole = record.is_object() && IsString(record, "name") && IsString(record, "path") &&
               record.contains("seed") && record.at("seed").is_number_unsigned() &&
               record.contains("runs") && record.at("runs").is_number_unsigned() &&
               record.contains("factors") && record.at("factors").is_array();
  for (const nlohmann::json& key : whole ? record.at("factors") : nlohmann::json::array()) {
    whole = whole && key.is_string();
  }
  if (whole && !record.contains("identity")) {
    throw OptionError(option,
                      where +
                          "was started by an earlier moorsim, which did not record its campaign's "
                          "identity; finish it with that moorsim or choose another directory");
  }
  if (whole) {
    const nlohmann::json& identity = record.at("identity");
    whole = identity.is_object() && IsString(identity, "sha256") && identity.contains("inputs") &&
            identity.at("inputs").is_array();
    for (const nlohmann::json& input : whole ? identity.at("inputs") : nlohmann::json::array()) {
      whole = whole && input.is_object() && IsString(input, "what") && IsString(input, "path") &&
              IsString(input, "sha256");
    }
  }
  if (!whole)
    throw OptionError(option,
                      where + "campaign.json is damaged (not the JSON moorsim batch writes)");
  return record;
}

// Empty when the identities `recorded` (DIR's) and `now` (as IdentityJson; the campaign
// resuming DIR, else the one merged into it) are one, else which input differs, in words:
// "the base scenario X changed since DIR was started". Inputs are paired by kind and
// order, not by path, so that a file found elsewhere is compared with the one it replaces.
std::string IdentityDifference(const nlohmann::json& recorded, const nlohmann::json& now,
                               const std::string& directory, bool resuming) {
  if (recorded.at("sha256") == now.at("sha256")) return "";
  const std::string campaign = resuming ? "this campaign" : "the merged campaign";
  // The input of `inputs[i]`'s kind and order in `other`, or nullptr.
  const auto counterpart = [](const nlohmann::json& inputs, std::size_t i,
                              const nlohmann::json& other) -> const nlohmann::json* {
    const nlohmann::json& what = inputs[i].at("what");
    std::size_t k = 0;
    for (std::size_t j = 0; j < i; ++j) k += inputs[j].at("what") == what ? 1 : 0;
    for (const nlohmann::json& input : other) {
      if (input.at("what") == what && k-- == 0) return &input;
    }
    return nullptr;
  };
  const nlohmann::json& was = recorded.at("inputs");
  const nlohmann::json& is = now.at("inputs");
  for (std::size_t i = 0; i < is.size(); ++i) {
    const std::string what = is[i].at("what"), path = is[i].at("path");
    const nlohmann::json* old = counterpart(is, i, was);
    if (old == nullptr) {
      return campaign + " reads the " + what + " " + path + ", which " + directory +
             " was not started with";
    }
    if (old->at("sha256") == is[i].at("sha256")) continue;
    const std::string old_path = old->at("path");
    if (what == kRelease) {
      return directory + " was started by moorsim " + old_path + ", this is moorsim " + path +
             " (a campaign is finished by the release that started it)";
    }
    if (old_path == path) {
      return "the " + what + " " + path +
             (resuming ? " changed since " + directory + " was started"
                       : " differs from the one " + directory + " was started with");
    }
    return "the " + what + " " + path + " differs from " + old_path + ", which " + directory +
           " was started with";
  }
  for (std::size_t i = 0; i < was.size(); ++i) {
    if (counterpart(was, i, is) == nullptr) {
      return directory + " was started with the " + was[i].at("what").get<std::string>() + " " +
             was[i].at("path").get<std::string>() + " too, which " + campaign + " does not read";
    }
  }
  return "its campaign identity " + recorded.at("sha256").get<std::string>() + " is not " +
         campaign + "'s " + now.at("sha256").get<std::string>();
}

// Under DIR's lock: checks that DIR holds nothing of a campaign or the results of the one
// `record` (as CampaignMeta) describes, and records that campaign there if DIR is new.
// Throws OptionError "out DIR: ..." naming what differs. `resuming`: by a batch, not a merge.
void ClaimDirectory(const std::filesystem::path& directory, const nlohmann::json& record,
                    const std::string& campaign_text, bool resuming) {
  const std::string where = " " + directory.string() + ": ";
  const std::string refused = where + "holds the results of another campaign: ";
  const std::string advice = "; choose another directory or remove this one";
  const std::filesystem::path text = directory / "campaign.yaml";
  std::error_code error;
  if (std::filesystem::exists(directory / "campaign.json", error)) {
    const nlohmann::json recorded = ReadCampaignRecord(directory, "out");
    const std::string difference = IdentityDifference(
        recorded.at("identity"), record.at("identity"), directory.string(), resuming);
    if (!difference.empty()) throw OptionError("out", refused + difference + advice);
  } else {
    // No record: a new directory, or one whose first batch stopped before it wrote one
    // (campaign.json comes first, then campaign.yaml, then rows).
    if (!std::filesystem::is_empty(directory / "rows", error) && !error) {
      throw OptionError(
          "out", where + "holds rows of a campaign but no campaign.json that says which" + advice);
    }
    if (std::filesystem::exists(text, error) && ReadSmallFile(text) != campaign_text) {
      throw OptionError("out", refused + "its campaign.yaml is another campaign's text" + advice);
    }
    WriteFileAtomically(directory / "campaign.json", record.dump(2) + "\n");
  }
  if (!std::filesystem::exists(text, error)) WriteFileAtomically(text, campaign_text);
}

// DIR/rows/*.json of the campaign whose identity is `identity`, of `runs` runs. Files
// whose name does not end in .json (a row being written) are not read.
std::vector<nlohmann::json> ReadRowsOf(const std::filesystem::path& directory,
                                       const std::string& identity, std::int64_t runs) {
  std::vector<nlohmann::json> rows;
  const std::filesystem::path dir = directory / "rows";
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) return rows;
  const std::string move = "; move it out of " + dir.string();
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::filesystem::path& path = entry.path();
    if (path.extension() != ".json") continue;
    const std::string where = path.string() + ": ";
    const std::string stem = path.stem().string();
    if (!entry.is_regular_file() || stem.size() < 8 ||
        stem.find_first_not_of("0123456789") != std::string::npos) {
      throw InputError(where + "not a row of moorsim batch (rows are files named NNNNNNNN.json)" +
                       move);
    }
    nlohmann::json row;
    try {
      row = nlohmann::json::parse(ReadSmallFile(path));
    } catch (const nlohmann::json::exception&) {
    }
    if (!row.is_object() || !row.contains("run") || !row.at("run").is_number_integer() ||
        !IsString(row, "status") || !IsString(row, "campaign") || !row.contains("factors") ||
        !row.at("factors").is_object() || !row.contains("detectors") ||
        !row.at("detectors").is_object()) {
      throw InputError(where +
                       "not a row of moorsim batch (damaged: not the JSON of a row); remove it to "
                       "have its run done again");
    }
    const std::int64_t run = row.at("run").get<std::int64_t>();
    if (RunName(run) != stem) {
      const std::size_t digits = std::min(stem.find_first_not_of('0'), stem.size() - 1);
      throw InputError(where + "holds run " + std::to_string(run) + ", not run " +
                       stem.substr(digits) + " (its name)" + move);
    }
    if (run >= runs) {
      throw InputError(where + "run " + std::to_string(run) + " is not one of the campaign's " +
                       std::to_string(runs) + " runs (0.." + std::to_string(runs - 1) + ")" + move);
    }
    if (row.at("campaign") != identity) {
      throw InputError(where + "a row of another campaign (its campaign identity is not " +
                       (directory / "campaign.json").string() + "'s)" + move);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Detector statistics.

StatisticTrace::StatisticTrace(std::string type, double failure_time)
    : statistic_(detectors::StatisticOf(type)), failure_time_(failure_time) {
  if (statistic_ != nullptr) {
    thresholds_.assign(statistic_->thresholds.begin(), statistic_->thresholds.end());
  }
  false_crossings_.assign(thresholds_.size(), 0);
  first_crossing_.assign(thresholds_.size(), kNaN);
}

void StatisticTrace::Add(double t, const std::vector<double>& score) {
  if (statistic_ == nullptr) return;
  const double x = statistic_->value(score);
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

RunTruth TruthOf(const scenarios::Scenario& s) {
  if (!s.vessel) {
    throw InputError(s.source_path +
                     ": a campaign runs `moorsim run`, which needs a vessel section");
  }
  RunTruth t;
  if (s.failure.line > 0) {
    t.failure_line = s.failure.line;
    t.failure_time = s.failure.time;
    t.failure_mode = ChoiceName(s.failure.mode);
  }
  t.duration = s.simulation.duration;
  t.num_lines = static_cast<int>(s.mooring.lines.size());
  for (const scenarios::DetectorEntry& d : s.detectors) {
    t.detectors.emplace_back(d.label.empty() ? d.type : d.label, d.type);
  }
  return t;
}

std::string RunLocation(const scenarios::Campaign& c, const scenarios::CampaignRun& run,
                        const std::string& what) {
  const scenarios::CampaignBlock& block = c.blocks[static_cast<std::size_t>(run.block)];
  std::string factors;
  for (const auto& [key, value] : run.factors) {
    factors.append(factors.empty() ? "" : ", ").append(key).append("=").append(value);
  }
  std::string where = c.source_path;
  if (block.mark.line > 0) {
    where.append(":").append(std::to_string(block.mark.line));
    where.append(":").append(std::to_string(block.mark.column));
  }
  where.append(": blocks.").append(block.name).append(": run ").append(std::to_string(run.index));
  if (!factors.empty()) where.append(" (").append(factors).append(")");
  return where.append(": ").append(what);
}

double PreparedCampaign::EstimatedDuration(std::int64_t index) const {
  for (std::size_t b = 0; b < campaign.blocks.size(); ++b) {
    const scenarios::CampaignBlock& block = campaign.blocks[b];
    const std::int64_t size = block.Runs();
    if (index < size) return block_durations[b];
    index -= size;
  }
  return 0.0;
}

namespace {

// The overrides of a run but its seed (the last): runs that differ only in their seed share
// one scenario load.
std::string ConfigurationOf(const scenarios::CampaignRun& run) {
  std::string configuration;
  for (std::size_t k = 0; k + 1 < run.overrides.size(); ++k) {
    configuration.append(run.overrides[k]).append("\n");
  }
  return configuration;
}

// A run's scenario and the truth its row records; InputError located at the run
// (RunLocation).
struct LoadedRun {
  scenarios::Scenario scenario;
  RunTruth truth;
};

LoadedRun LoadRun(const scenarios::Campaign& c, const scenarios::CampaignRun& run) {
  // A transient run whose instant is not yet known (checked before its intact run has run)
  // is loaded with one at 0 s: any instant in the run is checked alike.
  scenarios::CampaignRun loadable = run;
  if (c.blocks[static_cast<std::size_t>(run.block)].TakesIntactInstants() &&
      std::none_of(run.overrides.begin(), run.overrides.end(),
                   [](const std::string& o) { return o.starts_with("failure.time="); })) {
    scenarios::SetFailureTime(loadable, 0.0);
  }
  try {
    LoadedRun loaded{scenarios::LoadScenario(c.scenario_path, loadable.overrides), {}};
    loaded.truth = TruthOf(loaded.scenario);
    return loaded;
  } catch (const InputError& e) {
    throw InputError(RunLocation(c, run, e.what()));
  }
}

// The runs checked before the first (PreparedCampaign), in order, each once. Choices are
// found by drawing the block's runs in order until each value has appeared (or the block
// ends), asking `stop` as it goes.
std::vector<std::int64_t> RunsToCheck(const scenarios::Campaign& c,
                                      const std::function<int()>& stop) {
  using Kind = scenarios::CampaignFactor::Kind;
  std::vector<std::int64_t> runs;
  std::set<std::int64_t> seen;
  const auto add = [&](std::int64_t index) {
    if (seen.insert(index).second) runs.push_back(index);
  };
  std::int64_t start = 0;
  for (const scenarios::CampaignBlock& b : c.blocks) {
    const std::int64_t seeds = b.SeedsPerPoint();
    const std::int64_t size = b.Points() * seeds;
    add(start);
    // A listed value's point: in a grid, the others at their first value (the last listed
    // factor varies fastest); zipped, the value's position.
    std::vector<std::int64_t> stride(b.factors.size(), 0);
    std::int64_t next = 1;
    for (std::size_t i = b.factors.size(); i-- > 0;) {
      if (b.factors[i].kind != Kind::kValues) continue;
      stride[i] = b.zip ? 1 : next;
      if (!b.zip) next *= static_cast<std::int64_t>(b.factors[i].values.size());
    }
    for (std::size_t i = 0; i < b.factors.size(); ++i) {
      const scenarios::CampaignFactor& f = b.factors[i];
      if (f.kind == Kind::kValues) {
        for (std::size_t v = 0; v < f.values.size(); ++v) {
          add(start + static_cast<std::int64_t>(v) * stride[i] * seeds);
        }
      } else if (f.kind == Kind::kChoice) {
        std::set<std::string> wanted(f.values.begin(), f.values.end());
        for (std::int64_t k = start; k < start + size && !wanted.empty(); ++k) {
          if (const int signal = stop ? stop() : 0; signal != 0) throw PreparationStopped(signal);
          if (wanted.erase(scenarios::MakeCampaignRun(c, k).factors[i].second) > 0) add(k);
        }
      }
    }
    start += size;
  }
  return runs;
}

// A line on stderr while preparing takes more than a second: on a terminal rewritten in
// place every 0.5 s, elsewhere a line every 10 s.
class PreparationProgress {
 public:
  explicit PreparationProgress(bool enabled) : enabled_(enabled) {}
  void Show(std::size_t done, std::size_t total, bool last) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < std::chrono::seconds(1)) return;
    if (!last && now - shown_ < std::chrono::milliseconds(tty_ ? 500 : 10'000)) return;
    shown_ = now;
    std::fprintf(stderr, "%smoorsim batch: %s %zu/%zu configurations%s", tty_ ? "\r\033[K" : "",
                 last ? "checked" : "checking", done, total, tty_ && !last ? "" : "\n");
    std::fflush(stderr);
  }

 private:
  bool enabled_;
  bool tty_ = ::isatty(2) == 1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point shown_{};
};

}  // namespace

PreparedCampaign PrepareCampaign(const std::string& campaign_path,
                                 const std::function<int()>& stop_requested, bool progress) {
  PreparedCampaign p;
  p.campaign = scenarios::LoadCampaign(campaign_path);
  const scenarios::Campaign& c = p.campaign;
  const std::vector<std::int64_t> to_check = RunsToCheck(c, stop_requested);
  // Each configuration's duration, by its overrides but the seed.
  std::unordered_map<std::string, double> durations;
  // Detector configurations already built once (by the scenario's detector sections).
  std::set<std::string> detector_configurations;
  // The files the runs read beside the campaign and its scenario, each set sorted.
  std::set<std::string> bases, stems;
  PreparationProgress shown(progress);
  for (std::size_t i = 0; i < to_check.size(); ++i) {
    if (const int signal = stop_requested ? stop_requested() : 0; signal != 0) {
      throw PreparationStopped(signal);
    }
    shown.Show(i, to_check.size(), false);
    const scenarios::CampaignRun run = scenarios::MakeCampaignRun(c, to_check[i]);
    std::string configuration = ConfigurationOf(run);
    if (durations.count(configuration) > 0) continue;
    const LoadedRun loaded = LoadRun(c, run);
    const scenarios::Scenario& s = loaded.scenario;
    durations.emplace(std::move(configuration), loaded.truth.duration);
    try {
      std::string key;
      for (const scenarios::DetectorEntry& d : s.detectors) {
        key.append(d.type).append("/").append(d.label).append("/").append(d.plugin).append("/");
        for (const auto& [name, value] : d.parameters) {
          key.append(name).append("=").append(Shortest(value)).append(",");
        }
        key.append(";");
      }
      for (const std::string& o : run.overrides) {
        if (o.rfind("detection", 0) == 0 || o.rfind("detectors", 0) == 0 ||
            o.rfind("mooring", 0) == 0 || o.rfind("vessel", 0) == 0) {
          key.append(o).append(";");
        }
      }
      if (detector_configurations.insert(key).second) runner::CheckDetectors(s);
    } catch (const InputError& e) {
      throw InputError(RunLocation(c, run, e.what()));
    }
    p.checked_runs.push_back(run.index);
    for (const auto& [path, file] : s.origins) bases.insert(file);
    stems.insert(s.vessel->hydrodynamics);
    for (const scenarios::DetectorEntry& d : s.detectors) {
      if (!d.plugin.empty() && std::find(p.plugin_paths.begin(), p.plugin_paths.end(), d.plugin) ==
                                   p.plugin_paths.end()) {
        p.plugin_paths.push_back(d.plugin);
      }
    }
  }
  shown.Show(p.checked_runs.size(), p.checked_runs.size(), true);
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const std::int64_t first = c.FirstRunOf(k);
    p.block_durations.push_back(
        durations.at(ConfigurationOf(scenarios::MakeCampaignRun(c, first))));
    for (std::int64_t i = first;
         c.blocks[k].TakesIntactInstants() && i < first + c.blocks[k].Runs(); ++i) {
      const scenarios::CampaignRun run = scenarios::MakeCampaignRun(c, i);
      try {
        p.transients.emplace(i, *scenarios::TransientSourceOf(c, run));
      } catch (const InputError& e) {
        throw InputError(RunLocation(c, run, e.what()));
      }
    }
  }
  // The identity (CampaignIdentity, in its order). The kinds' names are part of the hash.
  CampaignIdentity& id = p.identity;
  const auto add = [&id](const std::string& what, const std::string& path,
                         const std::optional<std::string>& sha256) {
    id.inputs.push_back({what, path, sha256.value_or("absent")});
  };
  const std::string version = moorsim::kVersion;
  const std::string release = version.substr(0, version.find('+'));
  add(kRelease, release, Sha256Hex(release));
  add("campaign file", c.source_path, Sha256Hex(c.text));
  add("scenario", c.scenario_path, FileSha256(c.scenario_path));
  for (const std::string& base : bases) add("base scenario", base, FileSha256(base));
  for (const std::string& stem : stems) {
    for (const char* extension : vessel::kWamitExtensions) {
      add("hydrodynamics file", stem + extension, FileSha256(stem + extension));
    }
  }
  std::vector<std::string> plugins;
  for (const std::string& path : p.plugin_paths) {
    add("plugin", path, FileSha256(path));
    plugins.push_back(path);
  }
  for (const auto& library : detectors::RegisteredPluginLibraries()) {
    if (std::find(plugins.begin(), plugins.end(), library->path()) != plugins.end()) continue;
    add("plugin", library->path(), library->sha256());
    plugins.push_back(library->path());
  }
  std::string all;
  for (const CampaignIdentity::Input& input : id.inputs) {
    all.append(input.what).append("\t").append(input.sha256).append("\n");
  }
  id.sha256 = Sha256Hex(all);
  return p;
}

void DescribeCampaign(const PreparedCampaign& p, int threads, std::ostream& out) {
  const scenarios::Campaign& c = p.campaign;
  out << "campaign " << c.name << " (" << c.source_path << "): " << c.NumRuns() << " runs of "
      << c.scenario_path << ", campaign seed " << c.seed << "\n";
  for (const scenarios::CampaignBlock& b : c.blocks) {
    out << "  block " << b.name << ": " << b.Points() << " points x " << b.SeedsPerPoint()
        << " seeds = " << b.Runs() << " runs\n";
  }
  out << "run\tblock\tseed\tfailure\tduration\tfactors\n";
  std::string previous;  // the configuration `truth` is of
  RunTruth truth;
  double simulated_seconds = 0.0;
  for (std::int64_t i = 0; i < c.NumRuns(); ++i) {
    const scenarios::CampaignRun r = scenarios::MakeCampaignRun(c, i);
    std::string configuration = ConfigurationOf(r);
    if (i == 0 || configuration != previous) {
      truth = LoadRun(c, r).truth;
      previous = std::move(configuration);
    }
    simulated_seconds += truth.duration;
    out << r.index << "\t" << c.blocks[static_cast<std::size_t>(r.block)].name << "\t" << r.seed
        << "\t";
    if (const auto transient = p.transients.find(i); transient != p.transients.end()) {
      out << "line " << transient->second.line << " at its largest tension in run "
          << transient->second.intact_run;
    } else if (truth.failure_line > 0) {
      out << "line " << truth.failure_line << " at " << Shortest(truth.failure_time) << " s";
    } else {
      out << "none";
    }
    out << "\t" << Shortest(truth.duration) << " s\t";
    for (std::size_t k = 0; k < r.factors.size(); ++k) {
      out << (k ? " " : "") << r.factors[k].first << "=" << r.factors[k].second;
    }
    out << "\n";
  }
  const int n = std::max(1, threads);
  const double wall = simulated_seconds / kEstimatedRealTimeFactor / n;
  out << "total " << Shortest(simulated_seconds) << " simulated s; estimated wall time "
      << Duration(wall) << " on " << n << " thread" << (n > 1 ? "s" : "") << " (at about "
      << Shortest(kEstimatedRealTimeFactor)
      << "x real time per thread, the thesis plant with its detectors)\n";
}

// ---------------------------------------------------------------------------------------
// Rows and tables.

nlohmann::json MakeRow(const PreparedCampaign& p, const scenarios::CampaignRun& run,
                       const RunTruth* truth, const RunResult& result,
                       const std::vector<StatisticTrace>& traces, const std::string& out_dir) {
  const scenarios::Campaign& c = p.campaign;
  const RunTruth t = truth ? *truth : RunTruth{};
  nlohmann::json row;
  row["run"] = run.index;
  row["campaign"] = p.identity.sha256;
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
  // A rejected run has no summary.
  const nlohmann::json none = nlohmann::json::object();
  const nlohmann::json& summary = result.summary.is_object() ? result.summary : none;
  row["wall_time"] = summary.value("wall_time", 0.0);
  const nlohmann::json& summary_detectors =
      summary.contains("detectors") ? summary.at("detectors") : none;
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
  row["integrator"] = summary.value("integrator", nlohmann::json::object());
  row["station_keeping"] = summary.value("station_keeping", nlohmann::json::object());
  // The lines' extremes and fatigue damage, the vessel's largest offset (the design checks).
  if (summary.contains("design")) row["design"] = summary.at("design");
  return row;
}

std::vector<nlohmann::json> ReadRows(const std::filesystem::path& directory) {
  const nlohmann::json record = ReadCampaignRecord(directory, "out");
  return ReadRowsOf(directory, record.at("identity").at("sha256").get<std::string>(),
                    record.at("runs").get<std::int64_t>());
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

/// The failure time a transient run takes from its intact run's row, or why there is none.
std::variant<double, std::string> InstantOf(const nlohmann::json& intact,
                                            const scenarios::TransientSource& source) {
  const std::string run = "intact run " + std::to_string(source.intact_run);
  if (intact.value("status", "") != "ok") {
    return run + " ended " + intact.value("status", "without a status") +
           ": it gives no instant for line " + std::to_string(source.line) + " to part at";
  }
  const nlohmann::json* lines =
      intact.contains("design") ? &intact.at("design").at("lines") : nullptr;
  const auto k = static_cast<std::size_t>(source.line - 1);
  if (lines == nullptr || k >= lines->size() ||
      !lines->at(k).value("time_of_max_top_tension", nlohmann::json()).is_number()) {
    return run + " records no largest tension of line " + std::to_string(source.line);
  }
  return lines->at(k).at("time_of_max_top_tension").get<double>();
}

/// The runs of this process (rank 0, or the only process): the pending list, and every row
/// written to DIR/rows as it arrives, from this process's threads or another rank's. A
/// transient run that takes its instant from an intact run waits for that run's row (the
/// pending list holds the intact runs first).
class LocalRunSource final : public RunSource {
 public:
  LocalRunSource(const PreparedCampaign& campaign, std::vector<std::int64_t> pending,
                 const std::vector<nlohmann::json>& finished, std::filesystem::path rows,
                 Progress& progress)
      : campaign_(campaign),
        pending_(std::move(pending)),
        rows_(std::move(rows)),
        progress_(progress) {
    for (const std::int64_t run : pending_) {
      if (const auto t = campaign_.transients.find(run); t != campaign_.transients.end()) {
        needed_.insert(t->second.intact_run);
      }
    }
    for (const nlohmann::json& row : finished) {
      const std::int64_t run = row.at("run").get<std::int64_t>();
      if (needed_.count(run)) intact_rows_.emplace(run, row);
    }
    const std::set<std::int64_t> pending_runs(pending_.begin(), pending_.end());
    for (const std::int64_t run : needed_) {
      if (!intact_rows_.count(run) && !pending_runs.count(run)) {
        throw ContractError("batch: intact run " + std::to_string(run) +
                            " neither done nor pending");
      }
    }
  }

  NextRun Next() override {
    const std::lock_guard<std::mutex> guard(mutex_);
    while (next_ < pending_.size()) {
      const std::int64_t run = pending_[next_];
      const auto transient = campaign_.transients.find(run);
      if (transient == campaign_.transients.end()) {
        ++next_;
        return {.index = run};
      }
      const auto intact = intact_rows_.find(transient->second.intact_run);
      if (intact == intact_rows_.end()) return {.index = NextRun::kNotYet};
      ++next_;
      const std::variant<double, std::string> instant =
          InstantOf(intact->second, transient->second);
      if (const double* time = std::get_if<double>(&instant)) {
        return {.index = run, .failure_time = *time};
      }
      RunResult refused;
      refused.message = std::get<std::string>(instant);
      const scenarios::CampaignRun refused_run =
          scenarios::MakeCampaignRun(campaign_.campaign, run);
      WriteRow(run, MakeRow(campaign_, refused_run, nullptr, refused, {}, "").dump() + "\n", false);
    }
    return {};
  }
  void Deliver(std::int64_t run, const std::string& row, bool ok) override {
    const std::lock_guard<std::mutex> guard(mutex_);
    WriteRow(run, row, ok);
    if (needed_.count(run)) intact_rows_.emplace(run, nlohmann::json::parse(row));
  }
  std::int64_t done() const { return done_; }
  std::int64_t failed() const { return failed_; }
  double seconds_done() const { return seconds_done_; }

 private:
  void WriteRow(std::int64_t run, const std::string& row, bool ok) {
    WriteFileAtomically(rows_ / (RunName(run) + ".json"), row);
    ++done_;
    if (!ok) ++failed_;
    seconds_done_ += campaign_.EstimatedDuration(run);
    progress_.Update(done_, failed_, seconds_done_, false);
  }

  const PreparedCampaign& campaign_;
  std::vector<std::int64_t> pending_;
  std::filesystem::path rows_;
  Progress& progress_;
  std::set<std::int64_t> needed_;                       // intact runs a pending transient needs
  std::map<std::int64_t, nlohmann::json> intact_rows_;  // their rows, as they come
  std::mutex mutex_;
  std::size_t next_ = 0;
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
        const NextRun next = source.Next();
        if (next.index == NextRun::kNoRun) break;
        if (next.index == NextRun::kNotYet) {  // an intact run this one needs is running
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
          continue;
        }
        scenarios::CampaignRun run = scenarios::MakeCampaignRun(p.campaign, next.index);
        if (!std::isnan(next.failure_time)) scenarios::SetFailureTime(run, next.failure_time);
        std::shared_ptr<const scenarios::Scenario> scenario;
        RunTruth truth;
        try {
          LoadedRun loaded = LoadRun(p.campaign, run);
          scenario = std::make_shared<const scenarios::Scenario>(std::move(loaded.scenario));
          truth = std::move(loaded.truth);
        } catch (const InputError& e) {  // a value drawn for this run alone
          RunResult rejected;
          rejected.message = e.what();
          source.Deliver(run.index, MakeRow(p, run, nullptr, rejected, {}, "").dump() + "\n",
                         false);
          continue;
        }
        std::vector<StatisticTrace> traces;
        for (const auto& detector : truth.detectors) {
          traces.emplace_back(detector.second, truth.failure_line > 0 ? truth.failure_time : kNaN);
        }
        RunRequest request;
        request.scenario_path = p.campaign.scenario_path;
        request.overrides = run.overrides;
        request.scenario = scenario;
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
        source.Deliver(run.index, MakeRow(p, run, &truth, r, traces, "").dump() + "\n",
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
  // The decision travels as one integer: 0 go, else the status and signal of the stop.
  bool decided = false;
  const auto decide = [&](int code) {
    if (!decided) {
      decided = true;
      return BroadcastDecision(mpi, code);
    }
    return code;
  };
  const auto stop_code = [](const BatchResult& r) {
    return r.status == BatchStatus::kOk ? 0 : static_cast<int>(r.status) | (r.signal << 8);
  };
  const auto stopped_by = [&result](int code) {
    result.status = static_cast<BatchStatus>(code & 0xff);
    result.signal = code >> 8;
  };
  try {
    if (o.shard_count < 1 || o.shard_index < 0 || o.shard_index >= o.shard_count) {
      throw OptionError("shard", " " + std::to_string(o.shard_index + 1) + "/" +
                                     std::to_string(o.shard_count) +
                                     ": expected K/N with 1 <= K <= N");
    }
    if (!(o.run_timeout >= 0.0) || !std::isfinite(o.run_timeout)) {
      throw OptionError("run_timeout", " " + Shortest(o.run_timeout) + ": must be >= 0 seconds");
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
        stopped_by(go);
        return result;
      }
      std::unique_ptr<RunSource> remote = RemoteRunSource(mpi);
      const std::string error =
          RunWorkers(p, o, result.directory, *remote, threads, stop_signal, stop);
      NotifyFinished(mpi);
      if (!error.empty()) throw Error(error);
      if (stop_signal.load() > 0) {
        result.status = BatchStatus::kInterrupted;
        result.signal = stop_signal.load();
      }
      return result;
    }

    // 2. Rank 0 (or the only process) owns the directory: this campaign's or a new one.
    const output::DirectoryLock lock(result.directory);
    ClaimDirectory(result.directory, CampaignMeta(p), c.text, true);
    CreateDirectory(result.directory / "rows");

    // 3. What is left to do in this shard.
    // Transient runs that take their instants from intact runs come after all others, and
    // the intact runs they need are run here if DIR holds no row of them (another shard's).
    const std::vector<nlohmann::json> finished_rows =
        ReadRowsOf(result.directory, p.identity.sha256, c.NumRuns());
    std::set<std::int64_t> finished;
    for (const nlohmann::json& row : finished_rows)
      finished.insert(row.at("run").get<std::int64_t>());
    std::vector<std::int64_t> pending, transient;
    std::set<std::int64_t> needed;
    for (std::int64_t run = o.shard_index; run < c.NumRuns(); run += o.shard_count) {
      ++result.runs;
      if (finished.count(run)) {
        ++result.skipped;
      } else if (const auto t = p.transients.find(run); t != p.transients.end()) {
        transient.push_back(run);
        needed.insert(t->second.intact_run);
      } else {
        pending.push_back(run);
      }
    }
    for (const std::int64_t run : needed) {
      if (finished.count(run) || (run - o.shard_index) % o.shard_count == 0) continue;
      pending.push_back(run);  // another shard's
      ++result.runs;
    }
    pending.insert(pending.end(), transient.begin(), transient.end());

    // 4. The runs: this process's threads, and the other ranks through the service thread.
    // Each run owns everything it builds; shared are the prepared campaign (read only),
    // the next index, the counters and the rows directory.
    decide(0);
    double pending_seconds = 0.0;
    for (const std::int64_t k : pending) pending_seconds += p.EstimatedDuration(k);
    Progress progress(o.progress, result.runs, result.skipped, pending_seconds);
    LocalRunSource local(p, std::move(pending), finished_rows, result.directory / "rows", progress);
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
    const std::vector<nlohmann::json> rows =
        ReadRowsOf(result.directory, p.identity.sha256, c.NumRuns());
    WriteCampaignTables(result.directory, c.text, c.name, c.source_path, c.seed, c.FactorKeys(),
                        rows, o.command_line);
    WriteDesignTables(result.directory, c, rows);
    for (const nlohmann::json& row : rows) {
      const nlohmann::json error = StationKeepingValue(row, "heading_error_max_deg");
      result.heading_lost += error.is_number() && error.get<double>() > kHeadingLostDeg ? 1 : 0;
    }
    if (!first_error.empty()) throw Error(first_error);
    const int signal = stop_signal.load();
    if (signal > 0) {
      result.status = BatchStatus::kInterrupted;
      result.signal = signal;
      result.message = "stopped by signal " + std::to_string(signal) + " after " +
                       std::to_string(result.done) + " runs; the same command resumes";
    } else if (result.failed > 0) {
      result.status = BatchStatus::kRunsFailed;
      result.message = std::to_string(result.failed) + " of " + std::to_string(result.done) +
                       " runs did not finish ok (status and error in runs.csv)";
    }
  } catch (const PreparationStopped& e) {
    result.status = BatchStatus::kInterrupted;
    result.signal = e.signal();
    result.message = "stopped by signal " + std::to_string(e.signal()) +
                     " while preparing the runs; nothing was run";
  } catch (const InputError& e) {
    result.status = BatchStatus::kRejected;
    result.message = e.what();
    if (const auto* option = dynamic_cast<const OptionError*>(&e)) {
      result.option_error = std::make_shared<const OptionError>(*option);
    }
  } catch (const std::exception& e) {
    result.status = BatchStatus::kFailed;
    result.message = e.what();
  }
  try {
    // A rank 0 that failed before "go" releases the others with its status; ranks that
    // failed the same way (they read the same files) take part in the same broadcast.
    decide(stop_code(result));
  } catch (const std::exception&) {
  }
  return result;
}

MergeResult MergeCampaigns(const std::vector<std::filesystem::path>& directories,
                           const std::filesystem::path& out, const std::string& command_line) {
  if (directories.empty()) throw OptionError("merge", ": give at least one directory");
  // Every directory is read and checked before anything is written.
  nlohmann::json meta;
  std::string text;
  std::map<std::int64_t, nlohmann::json> rows;
  for (const std::filesystem::path& dir : directories) {
    const nlohmann::json record = ReadCampaignRecord(dir, "merge");
    const std::filesystem::path recorded = dir / "campaign.yaml";
    std::error_code error;
    if (!std::filesystem::is_regular_file(recorded, error)) {
      throw OptionError(
          "merge",
          " " + dir.string() + ": no campaign.yaml (not a results directory of moorsim batch)");
    }
    if (meta.is_null()) {
      meta = record;
      text = ReadSmallFile(recorded);
    }
    const std::string difference = IdentityDifference(meta.at("identity"), record.at("identity"),
                                                      directories.front().string(), false);
    if (!difference.empty()) {
      throw OptionError("merge", " " + dir.string() + ": holds another campaign than " +
                                     directories.front().string() + ": " + difference);
    }
    const std::string identity = meta.at("identity").at("sha256").get<std::string>();
    for (nlohmann::json& row : ReadRowsOf(dir, identity, meta.at("runs").get<std::int64_t>())) {
      const std::int64_t run = row.at("run").get<std::int64_t>();
      rows.emplace(run, std::move(row));
    }
  }
  const output::DirectoryLock lock(out);
  ClaimDirectory(out, meta, text, false);
  CreateDirectory(out / "rows");
  // The rows `out` holds already (an earlier merge, a shard merged into itself) stay rows.
  for (nlohmann::json& row : ReadRowsOf(out, meta.at("identity").at("sha256").get<std::string>(),
                                        meta.at("runs").get<std::int64_t>())) {
    const std::int64_t run = row.at("run").get<std::int64_t>();
    rows.emplace(run, std::move(row));
  }
  MergeResult result;
  result.runs = meta.at("runs").get<std::int64_t>();
  for (std::int64_t run = 0; run < result.runs; ++run) {
    if (!rows.contains(run)) result.missing.push_back(run);
  }
  std::vector<nlohmann::json> all;
  for (auto& [run, row] : rows) {
    WriteFileAtomically(out / "rows" / (RunName(run) + ".json"), row.dump() + "\n");
    all.push_back(std::move(row));
  }
  WriteDesignTables(out, scenarios::ParseCampaign(text, meta.at("path").get<std::string>(), false),
                    all);
  WriteCampaignTables(out, text, meta.at("name").get<std::string>(),
                      meta.at("path").get<std::string>(), meta.at("seed").get<std::uint64_t>(),
                      meta.at("factors").get<std::vector<std::string>>(), std::move(all),
                      command_line);
  return result;
}

}  // namespace moorsim::simulation
