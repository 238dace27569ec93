#include "detectors/fused.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "detectors/registry.h"

namespace moorsim::detectors {

Fused::Fused(const FusedOptions& options)
    : cells_(options.cells), pose_(options.pose), agreement_(options.agreement) {}

void Fused::Reset(int hypotheses) {
  internal::Require(hypotheses >= 1, "fused", "at least one hypothesis");
  hypotheses_ = hypotheses;
  cells_.Reset(hypotheses);
  pose_.Reset(hypotheses);
  agreement_.Reset();
  named_ = 0;
  named_by_pose_ = false;
  noisy_when_named_.clear();
  verdict_ = Verdict{std::vector<double>(static_cast<std::size_t>(hypotheses), 0.0), 0, false, {}};
}

bool Fused::CellSpeaks(const Evidence& evidence, int line) const {
  if (!evidence.tensions || line < 1 || line > evidence.tensions->measured.size()) return false;
  if (!std::isfinite(evidence.tensions->measured(line - 1))) return false;  // frozen, withheld
  if (line <= cells_.num_cells() && cells_.judged_faulty(line)) return false;
  return std::none_of(evidence.sensor_faults.begin(), evidence.sensor_faults.end(),
                      [line](const SensorFinding& f) {
                        // A noisy cell still speaks: the cells test averages its readings.
                        return f.sensor.kind == SensorId::Kind::kCell && f.sensor.line == line &&
                               f.symptom != SensorSymptom::kNoisy;
                      });
}

Verdict Fused::Update(const Evidence& evidence) {
  internal::CheckEvidence("fused", evidence, hypotheses_);
  // The pose against the cells that speak (as of the sample before). Only while the mooring
  // is the intact model's: from a cell reading low or a line named, the judgement stands
  // (a parting vessel's line dynamics make patterns of their own).
  bool pose_disagrees = agreement_.disagrees();
  if (evidence.tensions && named_ == 0) {
    const auto n = static_cast<int>(evidence.tensions->measured.size());
    counts_.assign(static_cast<std::size_t>(n), false);
    bool any_low = false;
    for (int line = 1; line <= n; ++line) {
      const bool low = line <= cells_.num_cells() && cells_.reads_low(line);
      any_low = any_low || low;
      counts_[static_cast<std::size_t>(line - 1)] = CellSpeaks(evidence, line) && !low;
    }
    if (!any_low) pose_disagrees = agreement_.Update(evidence, counts_);
  }
  const bool pose_trusted =
      !pose_disagrees &&
      std::none_of(evidence.sensor_faults.begin(), evidence.sensor_faults.end(),
                   [](const SensorFinding& f) { return f.sensor.kind != SensorId::Kind::kCell; });
  cells_.SetPoseTrusted(pose_trusted);
  const Verdict& cells = cells_.Step(evidence);
  const Verdict& pose = pose_.Step(evidence);
  const bool has_cells = evidence.tensions.has_value() && cells_.num_cells() > 0;

  // What the evidence names now (rules 1-3 of the file comment).
  int now = 0;
  bool by_pose = false;
  if (cells.alarm) {
    now = cells.hypothesis;
  } else if (!pose_trusted && cells_.unconfirmed() != 0) {
    now = cells_.unconfirmed();
  } else if (pose.alarm && pose_trusted && pose.hypothesis != 0) {
    const int h = pose.hypothesis;
    const bool single = has_cells && h <= cells_.num_cells();
    if (!has_cells || (single && !CellSpeaks(evidence, h))) {
      now = h;
      by_pose = true;
    }
  }
  // Rule 4: a named line stays named while its evidence stands.
  if (named_ != 0 && now == 0) {
    const bool stands = named_by_pose_
                            ? pose.alarm && pose.hypothesis == named_
                            : has_cells && named_ <= cells_.num_cells() && cells_.reads_low(named_);
    if (!stands) named_ = 0;
  } else if (now != 0) {
    named_ = now;
    named_by_pose_ = by_pose;
  }

  for (int h = 0; h < hypotheses_; ++h) {
    // The cells' deficit where they speak, else the pose's score.
    verdict_.score[static_cast<std::size_t>(h)] = has_cells
                                                      ? cells.score[static_cast<std::size_t>(h)]
                                                      : pose.score[static_cast<std::size_t>(h)];
  }
  verdict_.alarm = named_ != 0;
  verdict_.hypothesis = named_;
  // Once a line is named, the remaining lines carry more dynamic tension than their cells'
  // usual noise level holds: a cell judged noisy only from then on is not named.
  if (named_ == 0) {
    noisy_when_named_.clear();
    for (const SensorFinding& f : evidence.sensor_faults) {
      if (f.sensor.kind == SensorId::Kind::kCell && f.symptom == SensorSymptom::kNoisy) {
        noisy_when_named_.push_back(f.sensor.line);
      }
    }
  }
  verdict_.faulty_sensors.clear();
  for (const SensorFinding& f : evidence.sensor_faults) {
    const bool since_named = named_ != 0 && f.sensor.kind == SensorId::Kind::kCell &&
                             f.symptom == SensorSymptom::kNoisy &&
                             std::find(noisy_when_named_.begin(), noisy_when_named_.end(),
                                       f.sensor.line) == noisy_when_named_.end();
    if (!since_named) verdict_.faulty_sensors.push_back(f);
  }
  if (pose_disagrees) {
    verdict_.faulty_sensors.push_back(
        {.sensor = {.kind = agreement_.culprit()}, .symptom = SensorSymptom::kDisagrees});
  }
  for (const SensorFinding& f : cells.faulty_sensors) {
    // Rule 5: the named line's cell, declared faulty before the pose confirmed it.
    if (named_by_pose_ && f.sensor.kind == SensorId::Kind::kCell && f.sensor.line == named_ &&
        f.symptom == SensorSymptom::kDisagrees) {
      continue;
    }
    if (std::find(verdict_.faulty_sensors.begin(), verdict_.faulty_sensors.end(), f) ==
        verdict_.faulty_sensors.end()) {
      verdict_.faulty_sensors.push_back(f);
    }
  }
  return verdict_;
}

}  // namespace moorsim::detectors
