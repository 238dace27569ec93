#include "monitor/store.h"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/format.h"

namespace moorsim::monitor {

namespace fs = std::filesystem;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// One SQLite connection and its prepared statements.
struct Store::Database {
  sqlite3* db = nullptr;
  std::string path;

  explicit Database(const std::string& file) : path(file) {
    if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
        SQLITE_OK) {
      const std::string why = db ? sqlite3_errmsg(db) : "out of memory";
      sqlite3_close(db);
      throw InputError(file + ": cannot open the store: " + why);
    }
    sqlite3_busy_timeout(db, 2000);
    Exec("PRAGMA journal_mode=WAL");
    Exec("PRAGMA synchronous=FULL");
  }
  ~Database() {
    insert_line.reset();
    insert_sample.reset();
    sqlite3_close(db);
  }

  void Exec(const std::string& sql) {
    char* error = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string why = error ? error : "unknown error";
      sqlite3_free(error);
      throw Error(path + ": " + why + " (in: " + sql.substr(0, 60) + ")");
    }
  }

  /// A statement, bound and stepped by the callers.
  class Statement {
   public:
    Statement(Database& d, const std::string& sql) : d_(d) {
      if (sqlite3_prepare_v2(d.db, sql.c_str(), -1, &s_, nullptr) != SQLITE_OK) {
        throw Error(d.path + ": " + sqlite3_errmsg(d.db));
      }
    }
    ~Statement() { sqlite3_finalize(s_); }
    Statement& Bind(int i, double v) {
      std::isfinite(v) ? sqlite3_bind_double(s_, i, v) : sqlite3_bind_null(s_, i);
      return *this;
    }
    Statement& Bind(int i, std::int64_t v) {
      sqlite3_bind_int64(s_, i, v);
      return *this;
    }
    Statement& Bind(int i, int v) { return Bind(i, static_cast<std::int64_t>(v)); }
    Statement& Bind(int i, const std::string& v) {
      sqlite3_bind_text(s_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
      return *this;
    }
    Statement& BindOptional(int i, const std::optional<double>& v) {
      v ? sqlite3_bind_double(s_, i, *v) : sqlite3_bind_null(s_, i);
      return *this;
    }
    /// One step; true while it yields rows.
    bool Step() {
      const int status = sqlite3_step(s_);
      if (status == SQLITE_ROW) return true;
      if (status != SQLITE_DONE) throw Error(d_.path + ": " + sqlite3_errmsg(d_.db));
      return false;
    }
    void Run() {
      Step();
      sqlite3_reset(s_);
      sqlite3_clear_bindings(s_);
    }
    bool Null(int c) const { return sqlite3_column_type(s_, c) == SQLITE_NULL; }
    double Real(int c) const { return Null(c) ? kNaN : sqlite3_column_double(s_, c); }
    std::int64_t Integer(int c) const { return sqlite3_column_int64(s_, c); }
    std::string Text(int c) const {
      const unsigned char* text = sqlite3_column_text(s_, c);
      return text ? reinterpret_cast<const char*>(text) : "";
    }
    std::optional<double> MaybeReal(int c) const {
      return Null(c) ? std::nullopt : std::optional<double>(sqlite3_column_double(s_, c));
    }

   private:
    Database& d_;
    sqlite3_stmt* s_ = nullptr;
  };

  // The record's inserts, prepared once.
  std::unique_ptr<Statement> insert_line, insert_sample;

  std::string Meta(const std::string& key) {
    Statement s(*this, "SELECT value FROM meta WHERE key = ?");
    s.Bind(1, key);
    return s.Step() ? s.Text(0) : std::string();
  }
};

namespace {

constexpr const char* kMainSchema = R"(
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS alarms (
  id INTEGER PRIMARY KEY, number INTEGER NOT NULL, text TEXT NOT NULL, raised REAL NOT NULL,
  cleared REAL, acknowledged REAL, acknowledged_by TEXT);
CREATE TABLE IF NOT EXISTS events (id INTEGER PRIMARY KEY, unix REAL NOT NULL, line TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS health (id INTEGER PRIMARY KEY, unix REAL NOT NULL, what TEXT NOT NULL);
)";

constexpr const char* kRecordSchema = R"(
CREATE TABLE IF NOT EXISTS lines (
  id INTEGER PRIMARY KEY, unix_us INTEGER NOT NULL, feed INTEGER NOT NULL, text BLOB NOT NULL);
CREATE TABLE IF NOT EXISTS samples (
  k INTEGER PRIMARY KEY, segment INTEGER NOT NULL, t REAL NOT NULL,
  north REAL, east REAL, heading REAL,
  thrust_surge REAL NOT NULL, thrust_sway REAL NOT NULL, thrust_yaw REAL NOT NULL,
  tensions TEXT);
)";

std::int64_t DayOf(double unix_time) {
  return static_cast<std::int64_t>(std::floor(unix_time / 86400.0));
}

std::string RecordName(std::int64_t day) {
  const std::time_t seconds = static_cast<std::time_t>(day * 86400);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char name[40];
  std::snprintf(name, sizeof name, "record-%04d-%02d-%02d.db", utc.tm_year + 1900, utc.tm_mon + 1,
                utc.tm_mday);
  return name;
}

std::string TensionsText(const std::optional<VecX>& tensions) {
  if (!tensions) return "";
  std::string text;
  for (Eigen::Index i = 0; i < tensions->size(); ++i) {
    if (i > 0) text += ',';
    text += FormatNumber((*tensions)(i));
  }
  return text;
}

std::optional<VecX> TensionsOf(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::vector<double> values;
  std::stringstream in(text);
  std::string cell;
  while (std::getline(in, cell, ',')) values.push_back(std::stod(cell));
  return Eigen::Map<const VecX>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

Store::Store(const std::string& folder, const StoreIdentity& identity, double now, int keep_days)
    : folder_(folder), keep_days_(keep_days) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error || !fs::is_directory(folder)) {
    throw InputError(folder + ": cannot make the store's folder" +
                     (error ? ": " + error.message() : std::string()));
  }
  main_ = std::make_unique<Database>((fs::path(folder) / "monitor.db").string());
  main_->Exec(kMainSchema);
  const std::string scenario = main_->Meta("scenario_text");
  if (!scenario.empty()) {
    if (scenario != identity.scenario_text) {
      throw InputError(folder + ": the store of another scenario (" + main_->Meta("scenario_path") +
                       ", changed since); give the monitor a new store folder");
    }
    resumed_ = true;
    epoch_ = std::stod(main_->Meta("epoch"));
  } else {
    epoch_ = std::floor(now);
    main_->Exec("BEGIN");
    Database::Statement put(*main_, "INSERT OR REPLACE INTO meta VALUES (?, ?)");
    for (const auto& [key, value] :
         std::vector<std::pair<std::string, std::string>>{{"epoch", FormatNumber(epoch_)},
                                                          {"config_path", identity.config_path},
                                                          {"config_text", identity.config_text},
                                                          {"scenario_path", identity.scenario_path},
                                                          {"scenario_text", identity.scenario_text},
                                                          {"version", identity.version}}) {
      put.Bind(1, key).Bind(2, value).Run();
    }
    main_->Exec("COMMIT");
  }
  OpenRecord(now);
}

Store::~Store() {
  try {
    Commit();
  } catch (const std::exception&) {
  }
}

void Store::OpenRecord(double unix_time) {
  const std::int64_t day = DayOf(unix_time);
  if (day == record_day_) return;
  Commit();
  record_ = std::make_unique<Database>((fs::path(folder_) / RecordName(day)).string());
  record_->Exec(kRecordSchema);
  record_day_ = day;
  if (keep_days_ <= 0) return;
  // Records past their days go (their names sort by date: compare the names).
  // "record-YYYY-MM-DD", and the database's own files after it (.db, .db-wal, .db-shm).
  const std::string oldest_kept = RecordName(day - keep_days_ + 1).substr(0, 17);
  for (const fs::directory_entry& entry : fs::directory_iterator(folder_)) {
    const std::string name = entry.path().filename().string();
    const bool record =
        name.starts_with("record-") && name.size() >= 20 && name.compare(17, 3, ".db") == 0;
    if (record && name.substr(0, 17) < oldest_kept) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

namespace {

/// The alarm occurrences a query on the alarms table selects (its columns in order).
std::vector<Alarm> AlarmsOf(Store::Database& d, const std::string& where) {
  std::vector<Alarm> listed;
  Store::Database::Statement s(
      d, "SELECT id, number, text, raised, cleared, acknowledged, acknowledged_by FROM alarms " +
             where);
  while (s.Step()) {
    Alarm a;
    a.id = s.Integer(0);
    a.number = static_cast<int>(s.Integer(1));
    a.text = s.Text(2);
    a.raised = s.Real(3);
    a.cleared = s.MaybeReal(4);
    a.acknowledged = s.MaybeReal(5);
    a.acknowledged_by = s.Text(6);
    listed.push_back(std::move(a));
  }
  return listed;
}

}  // namespace

std::vector<Alarm> Store::ListedAlarms() {
  return AlarmsOf(*main_,
                  "WHERE id IN (SELECT MAX(id) FROM alarms GROUP BY number) AND (cleared IS NULL "
                  "OR acknowledged IS NULL) ORDER BY number");
}

std::vector<Alarm> ReadStoredAlarms(const std::string& folder) {
  ReadStoreEpoch(folder);
  Store::Database d((fs::path(folder) / "monitor.db").string());
  return AlarmsOf(d, "ORDER BY id");
}

void Store::SegmentStarted(std::int64_t segment) {
  Database::Statement put(*main_, "INSERT OR REPLACE INTO meta VALUES ('segment', ?)");
  put.Bind(1, std::to_string(segment)).Run();
}

std::int64_t Store::LastSegment() {
  // The number kept with the store's identity; the records' own, for a store from before.
  const std::string kept = main_->Meta("segment");
  std::int64_t last = kept.empty() ? 0 : std::stoll(kept);
  for (const std::int64_t day : {record_day_ - 1, record_day_}) {
    const fs::path path = fs::path(folder_) / RecordName(day);
    if (!fs::exists(path)) continue;
    if (day == record_day_) Commit();
    Database d(path.string());
    d.Exec(kRecordSchema);
    Database::Statement s(d, "SELECT MAX(segment) FROM samples");
    if (s.Step() && !s.Null(0)) last = std::max(last, s.Integer(0));
  }
  return last;
}

namespace {

/// The samples of one record file that `where` selects (bound to `low`, `high`), in order.
void ReadSamples(const std::string& path, const std::string& where, double low, double high,
                 std::optional<std::int64_t> segment, std::vector<StoredSample>* samples) {
  if (!fs::exists(path)) return;
  Store::Database d(path);
  Store::Database::Statement s(d,
                               "SELECT segment, k, t, north, east, heading, thrust_surge, "
                               "thrust_sway, thrust_yaw, tensions FROM samples WHERE " +
                                   where + " ORDER BY k");
  s.Bind(1, low).Bind(2, high);
  if (segment) s.Bind(3, *segment);
  while (s.Step()) {
    StoredSample x;
    x.segment = s.Integer(0);
    x.index = s.Integer(1);
    detectors::Observation& o = x.observation;
    o.t = s.Real(2);
    o.valid = {!s.Null(3), !s.Null(4), !s.Null(5)};
    o.pose =
        Vec3(s.Null(3) ? 0.0 : s.Real(3), s.Null(4) ? 0.0 : s.Real(4), s.Null(5) ? 0.0 : s.Real(5));
    o.tau_command = Vec3(s.Real(6), s.Real(7), s.Real(8));
    o.tensions = TensionsOf(s.Text(9));
    samples->push_back(std::move(x));
  }
}

}  // namespace

std::vector<StoredSample> Store::RecentSamples(double since) {
  Commit();
  const std::int64_t segment = LastSegment();
  std::vector<StoredSample> samples;
  for (const std::int64_t day : {record_day_ - 1, record_day_}) {
    ReadSamples((fs::path(folder_) / RecordName(day)).string(), "t >= ? AND t < ? AND segment = ?",
                since, 1e300, segment, &samples);
  }
  return samples;
}

double ReadStoreEpoch(const std::string& folder) {
  const fs::path path = fs::path(folder) / "monitor.db";
  if (!fs::is_regular_file(path)) {
    throw InputError(folder + ": not a monitor's store (no monitor.db)");
  }
  Store::Database d(path.string());
  const std::string epoch = d.Meta("epoch");
  if (epoch.empty()) throw InputError(folder + ": a monitor's store without its epoch");
  return std::stod(epoch);
}

StoreIdentity ReadStoreIdentity(const std::string& folder) {
  ReadStoreEpoch(folder);
  Store::Database d((fs::path(folder) / "monitor.db").string());
  StoreIdentity identity;
  identity.config_path = d.Meta("config_path");
  identity.config_text = d.Meta("config_text");
  identity.scenario_path = d.Meta("scenario_path");
  identity.scenario_text = d.Meta("scenario_text");
  identity.version = d.Meta("version");
  return identity;
}

std::vector<StoredSample> ReadStoredSamples(const std::string& folder, double from, double to) {
  const double epoch = ReadStoreEpoch(folder);
  std::vector<StoredSample> samples;
  if (!(to > from)) return samples;
  // Every day's record in order (their names sort by date).
  std::vector<std::string> records;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("record-") && name.ends_with(".db")) records.push_back(entry.path());
  }
  std::sort(records.begin(), records.end());
  constexpr double kBeyond = 1e300;
  for (const std::string& record : records) {
    ReadSamples(record, "t >= ? AND t < ?", std::max(-kBeyond, from - epoch),
                std::min(kBeyond, to - epoch), std::nullopt, &samples);
  }
  return samples;
}

void Store::Line(const FeedLine& line) {
  OpenRecord(line.stamp);
  if (!pending_) {
    record_->Exec("BEGIN");
    pending_ = true;
  }
  if (!record_->insert_line) {
    record_->insert_line = std::make_unique<Database::Statement>(
        *record_, "INSERT INTO lines (unix_us, feed, text) VALUES (?, ?, ?)");
  }
  Database::Statement& s = *record_->insert_line;
  s.Bind(1, static_cast<std::int64_t>(std::llround(line.stamp * 1e6)))
      .Bind(2, line.feed)
      .Bind(3, line.text)
      .Run();
}

void Store::SampleTaken(const Sample& sample, std::int64_t segment) {
  OpenRecord(epoch_ + sample.observation.t);
  if (!pending_) {
    record_->Exec("BEGIN");
    pending_ = true;
  }
  const detectors::Observation& o = sample.observation;
  if (!record_->insert_sample) {
    record_->insert_sample = std::make_unique<Database::Statement>(
        *record_, "INSERT OR REPLACE INTO samples VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  }
  Database::Statement& s = *record_->insert_sample;
  s.Bind(1, sample.index).Bind(2, segment).Bind(3, o.t);
  for (int i = 0; i < 3; ++i) s.Bind(4 + i, o.valid[i] ? o.pose(i) : kNaN);
  for (int i = 0; i < 3; ++i) s.Bind(7 + i, o.tau_command(i));
  if (o.tensions) {
    s.Bind(10, TensionsText(o.tensions));
  }
  s.Run();
}

void Store::Commit() {
  if (pending_ && record_) {
    record_->Exec("COMMIT");
    pending_ = false;
  }
}

std::int64_t Store::Change(const AlarmChange& change) {
  Commit();  // what led to it first
  const Alarm& a = change.alarm;
  if (change.kind == AlarmChange::Kind::kRaised) {
    Database::Statement s(*main_, "INSERT INTO alarms (number, text, raised) VALUES (?, ?, ?)");
    s.Bind(1, a.number).Bind(2, a.text).Bind(3, a.raised).Run();
    return sqlite3_last_insert_rowid(main_->db);
  }
  Database::Statement s(*main_,
                        "UPDATE alarms SET cleared = ?, acknowledged = ?, acknowledged_by = ? "
                        "WHERE id = ?");
  s.BindOptional(1, a.cleared).BindOptional(2, a.acknowledged);
  if (a.acknowledged) s.Bind(3, a.acknowledged_by);
  s.Bind(4, a.id).Run();
  return a.id;
}

void Store::Event(double unix_time, const std::string& json_line) {
  Commit();
  Database::Statement s(*main_, "INSERT INTO events (unix, line) VALUES (?, ?)");
  s.Bind(1, unix_time).Bind(2, json_line).Run();
}

void Store::Health(double unix_time, const std::string& what) {
  Database::Statement s(*main_, "INSERT INTO health (unix, what) VALUES (?, ?)");
  s.Bind(1, unix_time).Bind(2, what).Run();
}

}  // namespace moorsim::monitor
