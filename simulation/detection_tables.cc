#include "simulation/detection_tables.h"

#include <limits>
#include <span>
#include <string>

#include "core/types.h"
#include "detectors/registry.h"
#include "simulation/output_layout.h"

namespace moorsim::simulation {

namespace {

void AppendRow(output::Hdf5File& file, output::TableId table, const Vec3& v) {
  file.Append(table, std::span<const double>(v.data(), 3));
}

}  // namespace

DetectionTables::DetectionTables(output::Hdf5File& file, const Detection* detection) {
  if (detection != nullptr && detection->estimates_load()) {
    bias_ = layout::Create(file, layout::kObserverBias);
    wave_motion_ = layout::Create(file, layout::kObserverWaveMotion);
  }
  file.CreateGroup("/detectors");
  if (detection == nullptr) return;
  const std::vector<std::string> hypotheses = detection->HypothesisLabels();
  std::string joined;
  for (const std::string& h : hypotheses) joined += (joined.empty() ? "" : ",") + h;
  file.SetAttribute("/detectors", "hypotheses", joined);
  for (const DetectorRecord& d : detection->records()) {
    const std::string group = "/detectors/" + d.label;
    Tables t;
    // The scores' units are the detector type's, their columns the hypotheses.
    t.score = file.CreateTable(group + "/" + std::string(layout::kDetectorScore.path),
                               static_cast<int>(hypotheses.size()),
                               std::string(detectors::ScoreUnitsOf(d.type)), hypotheses);
    t.decision =
        layout::Create(file, layout::kDetectorDecision, 0, 0, group, output::TableType::kInt32);
    t.alarm = layout::Create(file, layout::kDetectorAlarm, 0, 0, group, output::TableType::kInt8);
    file.SetAttribute(group, "type", d.type);
    if (d.threshold) file.SetAttribute(group, "threshold", *d.threshold);
    detectors_.push_back(t);
  }
}

void DetectionTables::Append(output::Hdf5File& file, const std::optional<Vec3>& bias,
                             const std::optional<Vec3>& wave_motion,
                             const std::vector<detectors::Verdict>& verdicts) const {
  if (bias_) {
    AppendRow(file, *bias_, bias.value_or(Vec3::Constant(kNaN)));
    AppendRow(file, *wave_motion_, wave_motion.value_or(Vec3::Constant(kNaN)));
  }
  for (std::size_t i = 0; i < detectors_.size() && i < verdicts.size(); ++i) {
    const detectors::Verdict& v = verdicts[i];
    file.Append(detectors_[i].score, v.score);
    file.Append(detectors_[i].decision, static_cast<std::int32_t>(v.hypothesis));
    file.Append(detectors_[i].alarm, static_cast<std::int32_t>(v.alarm ? 1 : 0));
  }
}

}  // namespace moorsim::simulation
