#include "detectors/cells.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "detectors/registry.h"

namespace moorsim::detectors {

Cells::Cells(const CellsOptions& options) : options_(options) {
  if (options.window < 1) throw InputError("window must be >= 1");
  if (!(options.drop > 0.0 && options.drop < 1.0)) throw InputError("drop must be in (0, 1)");
}

void Cells::Reset(int hypotheses) {
  internal::Require(hypotheses >= 1, "cells", "at least one hypothesis");
  hypotheses_ = hypotheses;
  lines_.clear();
  bias_history_.clear();
  cell_faults_ = 0;
  pose_trusted_ = true;
  trusted_since_ = -std::numeric_limits<double>::infinity();
  unconfirmed_ = 0;
  verdict_ = Verdict{std::vector<double>(static_cast<std::size_t>(hypotheses), 0.0), 0, false, {}};
}

Cells::OtherCells Cells::ReadOtherCells(const TensionEvidence& cells, int k) const {
  OtherCells out;
  if (cells.expected_if_parted.cols() <= k) return out;
  for (Eigen::Index j = 0; j < cells.measured.size(); ++j) {
    const double parted = cells.expected_if_parted(j, k), intact = cells.expected(j);
    if (j == k || !std::isfinite(parted) || !(intact > 0.0)) continue;
    if (std::abs(cells.measured(j) - parted) > options_.drop * intact) {
      out.explained = false;
      out.corroborated = false;
      return out;
    }
    if (std::abs(parted - intact) > options_.drop * intact) out.corroborated = true;
  }
  return out;
}

Verdict Cells::Update(const Evidence& evidence) { return Step(evidence); }

const Verdict& Cells::Step(const Evidence& evidence) {
  internal::CheckEvidence("cells", evidence, hypotheses_);
  if (!evidence.tensions || !evidence.load) return verdict_;
  const TensionEvidence& cells = *evidence.tensions;
  const LoadEvidence& load = *evidence.load;
  const int n = static_cast<int>(cells.measured.size());
  internal::Require(cells.expected.size() == cells.measured.size(), "cells",
                    "as many expected tensions as readings");
  if (lines_.empty()) lines_.resize(static_cast<std::size_t>(n));
  internal::Require(static_cast<int>(lines_.size()) == n, "cells", "the same number of cells");
  const auto window = static_cast<std::size_t>(options_.window);
  bias_history_.push_back(load.bias);
  if (bias_history_.size() > window + 1) bias_history_.pop_front();

  const double t = evidence.t;
  if (!pose_trusted_) trusted_since_ = t;
  int best = 0;
  double best_ratio = 1.0;
  unconfirmed_ = 0;
  double unconfirmed_ratio = 1.0;
  for (int k = 0; k < n; ++k) {
    Line& line = lines_[static_cast<std::size_t>(k)];
    const double expected = cells.expected(k);
    const double ratio = expected > 0.0 ? cells.measured(k) / expected : 1.0;
    line.ratios.push_back(std::isfinite(ratio) ? ratio : 1.0);
    if (line.ratios.size() > window) line.ratios.pop_front();
    double mean = 0.0;
    for (double r : line.ratios) mean += r;
    mean /= static_cast<double>(line.ratios.size());
    const int h = k + 1;  // hypothesis "line k + 1 parted"
    if (h < hypotheses_) verdict_.score[static_cast<std::size_t>(h)] = 1.0 - mean;
    const bool low = line.ratios.size() == window && mean < 1.0 - options_.drop;
    // The mean fall_time ago: the newest one at least that old (none: the record is shorter).
    line.means.emplace_back(t, mean);
    while (line.means.size() > 1 && line.means[1].first <= t - options_.fall_time) {
      line.means.pop_front();
    }
    if (line.faulty) {
      if (mean > 1.0 - options_.drop / 2.0) line.faulty = false;  // reads true again
      line.low = false;
      continue;
    }
    if (low && !line.low) {
      const bool fell =
          options_.fall_time <= 0.0 || (line.means.front().first <= t - options_.fall_time &&
                                        line.means.front().second >= 1.0 - options_.drop / 2.0);
      if (!fell) {  // a drift, not a parted line
        line.faulty = true;
        ++cell_faults_;
        continue;
      }
      line.low_since = t;
      line.bias_before = bias_history_.front();
      line.low_samples = 0;
      line.settled_max = -std::numeric_limits<double>::infinity();
    }
    line.low = low;
    if (!low) line.confirmed = line.agreeing = false;
    // Once the window holds only readings from the low spell: its highest mean so far.
    if (low && ++line.low_samples > options_.window) {
      line.settled_max = std::max(line.settled_max, mean);
    }
    if (!low || t - line.low_since < options_.hold || h >= hypotheses_) continue;
    const OtherCells others = ReadOtherCells(cells, k);
    if (!others.explained) {
      // Another line of its network parted, or (no other cell reading low) this cell is
      // wrong: the others read as they would with its line intact.
      bool others_low = false;
      for (int j = 0; j < n; ++j) others_low |= j != k && lines_[static_cast<std::size_t>(j)].low;
      if (!others_low && t - line.low_since >= options_.confirm_time) {
        line.faulty = true;
        line.low = false;
        ++cell_faults_;
      }
      continue;
    }
    bool agrees = true;
    if (options_.confirm && !line.confirmed && !others.corroborated) {
      const Eigen::Vector2d lost = load.line_load[static_cast<std::size_t>(h)].head<2>();
      const double size = lost.norm();
      const double shift =
          size > 0.0 ? -(load.bias - line.bias_before).head<2>().dot(lost) / size : 0.0;
      const bool shows = shift >= std::max(options_.confirm_fraction * (1.0 - mean) * size,
                                           options_.confirm_floor);
      if (shows && !line.agreeing) line.agree_since = t;
      line.agreeing = shows;
      // A cell that still reads more than half: the reading must be falling still.
      const bool falling = options_.anchor_fall <= 0.0 || mean <= 0.5 ||
                           line.settled_max - mean >= options_.anchor_fall;
      agrees = shows && falling && t - line.agree_since >= options_.confirm_hold;
      if (!agrees && pose_trusted_ &&
          t - std::max(line.low_since, trusted_since_) >= options_.confirm_time) {
        line.faulty = true;  // the vessel never felt it: the cell, not the line
        line.low = false;
        ++cell_faults_;
        continue;
      }
      line.confirmed = agrees;
    }
    if (agrees && mean < best_ratio) {
      best = h;
      best_ratio = mean;
    }
    if (!agrees && mean < unconfirmed_ratio) {
      unconfirmed_ = h;
      unconfirmed_ratio = mean;
    }
  }
  verdict_.alarm = best != 0;
  verdict_.hypothesis = best;
  verdict_.faulty_sensors.clear();
  for (int k = 0; k < n; ++k) {
    if (lines_[static_cast<std::size_t>(k)].faulty) {
      verdict_.faulty_sensors.push_back({.sensor = {.kind = SensorId::Kind::kCell, .line = k + 1},
                                         .symptom = SensorSymptom::kDisagrees});
    }
  }
  return verdict_;
}

}  // namespace moorsim::detectors
