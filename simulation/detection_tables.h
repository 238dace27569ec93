// The detection's tables in run.h5 and in `moorsim detect`'s detect.h5 (docs/design.md
// section 7), one row per output instant: the intact observer's load picture
// (/observer/bias, /observer/wave_motion; EKF bank only) and per detector its scores,
// decision and alarm (/detectors/<label>/score, decision, alarm), with the hypotheses'
// labels on /detectors.
#pragma once

#include <optional>
#include <vector>

#include "core/types.h"
#include "detectors/detector.h"
#include "io/hdf5_file.h"
#include "simulation/detection.h"

namespace moorsim::simulation {

class DetectionTables {
 public:
  /// Creates the tables in `file`; without a detection (nullptr) only an empty /detectors.
  DetectionTables(output::Hdf5File& file, const Detection* detection);
  /// One row: the load picture (NaN before the bank's first sample) and every verdict.
  void Append(output::Hdf5File& file, const std::optional<Vec3>& bias,
              const std::optional<Vec3>& wave_motion,
              const std::vector<detectors::Verdict>& verdicts) const;

 private:
  struct Tables {
    output::TableId score, decision, alarm;
  };
  std::optional<output::TableId> bias_, wave_motion_;
  std::vector<Tables> detectors_;
};

}  // namespace moorsim::simulation
