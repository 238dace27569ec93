// Recorded and live detection input for `moorsim detect`: the measured pose and the thrust a
// vessel delivered, one sample per row, read from a CSV stream (a log file, or rows
// arriving on standard input) or from the detection input a moorsim run recorded in its
// run.h5 (/detection/input). Each row becomes the detectors::Observation the simulation
// itself would have given the detection at that instant.
//
// CSV (a header line is required; columns in any order, matched by name; SI units):
//   time            [s]     strictly increasing
//   north, east     [m]     measured position (NED); empty = the GNSS gave nothing
//   heading         [rad]   measured heading; empty = the gyro gave nothing
//   thrust_surge, thrust_sway [N], thrust_yaw [N m]
//                           the thrust the allocation sent to the thrusters at this sample,
//                           body frame, held until the next row (required in every row)
//   tension_1 .. tension_N [N]   optional fairlead load cells (all N or none; a row with
//                           all of them empty has no reading)
// Lines that are empty or start with '#' are skipped; other columns are refused (a
// misspelt name would otherwise drop a channel unnoticed). A UTF-8 byte-order mark at the
// start of the stream (Excel writes one) is skipped; a NUL byte anywhere is an error.
//
// Gaps: an empty position or heading cell is a dropout the observers predict through, as
// they do for the simulated sensors' dropouts. A channel that stays empty, or a time step
// between rows, longer than the stated maximum gap is an error: the observers' prediction
// is then no longer worth a verdict.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "core/types.h"
#include "detectors/detector.h"

namespace moorsim::simulation {

/// The default maximum gap [s]: a minute without a channel (the drift of a dropped GNSS is
/// then of the order of the position noise times the filter's settling).
inline constexpr double kDefaultMaxGap = 60.0;

/// Checks a stream of observations as it goes: finite values, strictly increasing time,
/// no time step and no channel gap longer than the maximum. Messages start with `where`
/// ("run.h5 /detection/input row 12" or "log.csv:13").
class StreamChecks {
 public:
  explicit StreamChecks(double max_gap) : max_gap_(max_gap) {}
  /// Throws InputError "<where>: column '<name>': ..." on a broken sample.
  void Check(const detectors::Observation& o, const std::string& where);
  double max_gap() const { return max_gap_; }

 private:
  double max_gap_;
  double last_time_ = kNaN;
  std::array<double, 3> last_valid_ = {0.0, 0.0, 0.0};
};

/// A CSV stream read one line at a time (so that rows can be taken as they arrive).
class CsvPoseStream {
 public:
  /// `name` names the stream in messages; `lines` is the scenario's number of mooring
  /// lines (the tension columns' count).
  CsvPoseStream(std::string name, int lines, double max_gap);

  /// Takes the next line of the stream (1-based numbering; the header counts). Returns true
  /// and fills `observation` for a data row; false for the header, a comment or an empty
  /// line. Throws InputError "<name>:<line>: column '<name>': <what>" on bad input.
  bool Take(const std::string& line, detectors::Observation* observation);
  /// The stream goes on in a new file (a followed log was rotated): lines are numbered from
  /// 1 again, and the new file may start with the same header line, which is then skipped.
  /// The checks between rows (time increasing, gaps) go on across the rotation.
  void Restart();
  /// Lines taken so far (since the last Restart).
  long line_number() const { return line_number_; }
  /// Whether the header has been read.
  bool has_header() const { return have_header_; }
  /// Whether the header named tension columns.
  bool has_tensions() const { return !tension_columns_.empty(); }

 private:
  void Header(const std::vector<std::string>& cells);

  std::string name_;
  int lines_;
  StreamChecks checks_;
  long line_number_ = 0;
  bool have_header_ = false;
  bool header_may_repeat_ = false;
  std::vector<std::string> header_;
  // Column index of time, north, east, heading, thrust_surge, thrust_sway, thrust_yaw.
  std::array<int, 7> columns_ = {-1, -1, -1, -1, -1, -1, -1};
  std::vector<int> tension_columns_;
};

/// Every observation of a run.h5's /detection/input, checked as a CSV stream is; `lines` is
/// the scenario's number of mooring lines (the tension table's width). Throws InputError
/// naming the file and row for a file without the tables (written before moorsim recorded
/// them, or by a run without detectors), a table of the wrong length or width, or a broken
/// sample.
std::vector<detectors::Observation> ReadRunDetectionInput(const std::string& path, int lines,
                                                          double max_gap);

}  // namespace moorsim::simulation
