// The tables of run.h5 (`moorsim run`) and detect.h5 (`moorsim detect`), docs/design.md
// section 7: each table's path, width, units and column names, declared once here. The
// writers (run.cc, detection_tables.cc, the detect command) create their tables from these
// declarations and the readers (the replay of a run's detection input, pose_stream.cc; the
// Python module's read_run) check a file against them.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "io/hdf5_file.h"
#include "io/hdf5_reader.h"

namespace moorsim::simulation::layout {

/// A table's width where it is not fixed.
inline constexpr int kSeries = 0;          ///< one value per row (a one-dimensional dataset)
inline constexpr int kPerLine = -1;        ///< one column per mooring line, "line 1", ...
inline constexpr int kPerHypothesis = -2;  ///< one column per hypothesis of the bank

struct Table {
  /// The dataset's path; for a detector's tables, relative to its group /detectors/<label>.
  std::string_view path;
  int width;  ///< columns, or kSeries, kPerLine, kPerHypothesis
  /// The "units" attribute: per column, comma-separated, or one for every column.
  std::string_view units;
  /// The "columns" attribute, comma-separated (empty: a series, or generated per line).
  std::string_view columns;
};

// run.h5, one row per output instant.
inline constexpr Table kTime{"/time", kSeries, "s", ""};
inline constexpr Table kPoseTrue{"/vessel/pose_true", 6, "m,m,m,rad,rad,rad",
                                 "x,y,z,phi,theta,psi"};
inline constexpr Table kPoseLowFrequency{"/vessel/pose_low_frequency", 6, "m,m,m,rad,rad,rad",
                                         "x,y,z,phi,theta,psi"};
inline constexpr Table kVelocityTrue{"/vessel/velocity_true", 6, "m/s,m/s,m/s,rad/s,rad/s,rad/s",
                                     "u,v,w,p,q,r"};
inline constexpr Table kPoseMeasured{"/vessel/pose_measured", 3, "m,m,rad", "x,y,psi"};
inline constexpr Table kTurret{"/vessel/turret", 4, "rad,rad/s,N m,N m",
                               "angle,rate,moment_lines,moment_bearing"};
inline constexpr Table kFairleadTension{"/mooring/fairlead_tension", kPerLine, "N", ""};
inline constexpr Table kTensionMeasured{"/mooring/tension_measured", kPerLine, "N", ""};
/// One row per line, written once.
inline constexpr Table kAnchors{"/mooring/anchors", 3, "m,m,m", "x,y,z"};
inline constexpr Table kThrustCommanded{"/thrust/commanded", 3, "N,N,N m", "X,Y,N"};
inline constexpr Table kThrustDelivered{"/thrust/delivered", 3, "N,N,N m", "X,Y,N"};
inline constexpr Table kLoadMooring{"/environment/mooring", 6, "N,N,N,N m,N m,N m", "X,Y,Z,K,M,N"};
inline constexpr Table kLoadWavesDrift{"/environment/waves_drift", 6, "N,N,N,N m,N m,N m",
                                       "X,Y,Z,K,M,N"};
inline constexpr Table kLoadCurrent{"/environment/current", 6, "N,N,N,N m,N m,N m", "X,Y,Z,K,M,N"};
inline constexpr Table kLoadWind{"/environment/wind", 6, "N,N,N,N m,N m,N m", "X,Y,Z,K,M,N"};
inline constexpr Table kLoadThrust{"/environment/thrust", 6, "N,N,N,N m,N m,N m", "X,Y,Z,K,M,N"};

// The detection's samples as it took them (run.h5), one row per sample: what `moorsim
// detect RUN.h5` replays. A measured channel that delivered nothing is NaN.
inline constexpr Table kInputTime{"/detection/input/time", kSeries, "s", ""};
inline constexpr Table kInputPose{"/detection/input/pose_measured", 3, "m,m,rad", "x,y,psi"};
inline constexpr Table kInputThrust{"/detection/input/thrust", 3, "N,N,N m", "X,Y,N"};
inline constexpr Table kInputTension{"/detection/input/tension_measured", kPerLine, "N", ""};

// The detection's picture (run.h5 and detect.h5), one row per output instant.
inline constexpr Table kObserverBias{"/observer/bias", 3, "N,N,N m", "X,Y,N"};
inline constexpr Table kObserverWaveMotion{"/observer/wave_motion", 3, "m,m,rad", "x,y,psi"};
/// Units: the detector type's (detectors::ScoreUnitsOf); columns: the hypotheses' labels.
inline constexpr Table kDetectorScore{"score", kPerHypothesis, "", ""};
inline constexpr Table kDetectorDecision{"decision", kSeries, "hypothesis (0 = intact, k = line k)",
                                         ""};
inline constexpr Table kDetectorAlarm{"alarm", kSeries, "0/1", ""};

/// Every table above, in the order listed (the Python module's read_run checks them).
std::span<const Table> Tables();

/// The table's number of columns for a mooring of `lines` lines and a bank of
/// `hypotheses` hypotheses (kSeries: 0).
int Columns(const Table& table, int lines, int hypotheses = 0);

/// Creates `table` in `file` (under `group` for a detector's table), with its units and
/// column names ("line 1", ... for a table per line).
output::TableId Create(output::Hdf5File& file, const Table& table, int lines = 0,
                       int hypotheses = 0, const std::string& group = "",
                       output::TableType type = output::TableType::kFloat64);

/// Reads `table` from `file` (named `file_name` in the messages) and checks its width for
/// `lines` lines. Throws InputError "<file>: <path>: <n> columns, expected <m> (...)".
output::TableData Read(const output::Hdf5Reader& file, const std::string& file_name,
                       const Table& table, int lines = 0);

}  // namespace moorsim::simulation::layout
