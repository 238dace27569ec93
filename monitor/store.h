// The monitor's record: everything it received and decided, in SQLite databases in write-
// ahead-log mode, so that a kill at any moment (SIGKILL, a crash, a power loss) leaves them
// readable with every committed row.
//
//   STORE/monitor.db          who and what (the configuration, the scenario, the epoch),
//                             every alarm occurrence with its acknowledgement, every
//                             detector event (the JSON alarm lines) and the feeds' and
//                             channels' health changes; kept whole
//   STORE/record-YYYY-MM-DD.db  one per UTC day: every line read (with its feed and the
//                             microsecond it was read) and every sample the detection took
//                             (its instant, segment and values as `moorsim detect` reads
//                             them)
//
// Durability: an alarm change or a detector event is committed (synchronous=FULL) before
// it is printed or sent, so nothing announced is ever lost; the lines and samples are
// committed every second (Store::Commit), so a kill loses at most the last second of them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "detectors/detector.h"
#include "monitor/alarms.h"
#include "monitor/feeds.h"
#include "monitor/ingest.h"

namespace moorsim::monitor {

/// What a store was made for: a store is reused only by the same scenario.
struct StoreIdentity {
  std::string config_path, config_text;
  std::string scenario_path, scenario_text;
  std::string version;
};

/// A sample as stored, with its detection segment.
struct StoredSample {
  std::int64_t segment = 0;
  std::int64_t index = 0;
  detectors::Observation observation;
};

class Store {
 public:
  /// Opens the store in `folder` (made if absent), or starts one. Throws InputError naming
  /// the folder if it cannot be written, or if it is another scenario's store (a restart
  /// with a changed scenario would mix two vessels' records). `now`: UNIX time, whose whole
  /// second becomes a new store's epoch. `keep_days` > 0: each day's record is deleted
  /// once it is that many days older than the newest (0: every record is kept).
  Store(const std::string& folder, const StoreIdentity& identity, double now, int keep_days = 0);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  /// UNIX time of the sample clock's instant 0.
  double epoch() const { return epoch_; }
  /// Whether the store was there before (a restart).
  bool resumed() const { return resumed_; }
  const std::string& folder() const { return folder_; }

  /// The alarms that were listed (active, or not yet acknowledged) when the store was last
  /// written.
  std::vector<Alarm> ListedAlarms();
  /// The last segment's samples from `since` [s of the sample clock] on, in order, from
  /// this day's and the previous day's record.
  std::vector<StoredSample> RecentSamples(double since);
  /// The highest segment number stored (0 for none).
  std::int64_t LastSegment();
  /// A detection segment starts: its number is kept, so that a restart after any outage
  /// numbers the next one after it.
  void SegmentStarted(std::int64_t segment);

  /// A line read (kept until Commit).
  void Line(const FeedLine& line);
  /// A sample taken (kept until Commit).
  void SampleTaken(const Sample& sample, std::int64_t segment);
  /// Commits the lines and samples.
  void Commit();
  /// Records an alarm change at once (durable when it returns); returns the occurrence's
  /// id (a new one for a raise).
  std::int64_t Change(const AlarmChange& change);
  /// Records a detector's event (a JSON alarm line) at once.
  void Event(double unix_time, const std::string& json_line);
  /// A health change ("feed gnss: connected", "channel heading: stale").
  void Health(double unix_time, const std::string& what);

  /// One SQLite connection (store.cc).
  struct Database;

 private:
  void OpenRecord(double unix_time);
  std::string folder_;
  double epoch_ = 0.0;
  bool resumed_ = false;
  std::unique_ptr<Database> main_;
  std::unique_ptr<Database> record_;

  std::int64_t record_day_ = -1;
  int keep_days_ = 0;
  bool pending_ = false;
};

/// The samples a store recorded between `from` and `to` (UNIX times), in order, with
/// their segment; the scenario text the store was made for. Throws InputError naming the
/// store for a folder that is not one.
std::vector<StoredSample> ReadStoredSamples(const std::string& folder, double from, double to);
StoreIdentity ReadStoreIdentity(const std::string& folder);
/// Every alarm occurrence a store recorded, in the order they were raised.
std::vector<Alarm> ReadStoredAlarms(const std::string& folder);
double ReadStoreEpoch(const std::string& folder);

}  // namespace moorsim::monitor
