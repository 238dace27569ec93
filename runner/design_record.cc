#include "runner/design_record.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "analysis/extremes.h"

namespace moorsim::runner {
namespace {

nlohmann::json NumberOrNull(const std::optional<double>& x) {
  return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
}

struct Moments {
  double mean = 0.0, std_dev = 0.0;
};

Moments MomentsOf(const std::vector<double>& x) {
  Moments m;
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  double square = 0.0;
  for (double v : x) square += (v - m.mean) * (v - m.mean);
  m.std_dev = std::sqrt(square / static_cast<double>(x.size()));
  return m;
}

// The Weibull fit of a record's peaks above its mean plus one standard deviation, measured
// from its mean: the extremes of one long run (a campaign scales it to a storm's length).
// `m`: the record's moments. Null for fewer than 10 peaks or a fit that does not converge.
nlohmann::json PeaksFit(const std::vector<double>& x, const Moments& m) {
  if (x.size() < 2) return nullptr;
  const double threshold = m.mean + m.std_dev;
  const std::vector<double> peaks = analysis::PeaksOverThreshold(x, threshold);
  if (!(m.std_dev > 0.0) || peaks.size() < 10) return nullptr;
  try {
    const analysis::WeibullFit fit = analysis::FitWeibull(peaks, threshold, m.mean);
    return {{"threshold", fit.threshold},
            {"location", fit.location},
            {"scale", fit.scale},
            {"shape", fit.shape},
            {"covariance", {fit.covariance(0, 0), fit.covariance(0, 1), fit.covariance(1, 1)}},
            {"peaks", peaks.size()}};
  } catch (const std::invalid_argument&) {
    return nullptr;
  }
}

}  // namespace

DesignRecord::DesignRecord(const scenarios::Scenario& scenario, simulation::Simulation& sim)
    : from_(scenario.simulation.statistics_from), output_rate_(scenario.simulation.output_rate) {
  if (scenario.failure.line > 0) failure_time_ = scenario.failure.time;
  const auto place_of = [&](const std::string& type_name) {
    Place place;
    place.type = type_name;
    for (const scenarios::LineType& type : scenario.mooring.line_types) {
      if (type.name != type_name) continue;
      place.breaking = type.minimum_breaking_load;
      if (type.fatigue_curve) {
        place.fatigue = analysis::FatigueComponent{*type.fatigue_curve, type.fatigue_area,
                                                   type.minimum_breaking_load};
      }
    }
    return place;
  };
  const std::vector<std::vector<Vec3>> nodes = sim.NodePositions();
  const mooring_fem::SeabedContact& seabed = sim.mooring().seabed();
  for (std::size_t k = 0; k < scenario.mooring.lines.size(); ++k) {
    const scenarios::LineSpec& spec = scenario.mooring.lines[k];
    const mooring_fem::LineProperties& properties = sim.mooring().line(static_cast<int>(k));
    Line line;
    line.top = place_of(spec.sections.back().type);
    // The touchdown: the first segment from the anchor whose upper node is off the seabed
    // (more than 0.1 m above it); the bottom segment of a line that never touches it.
    const std::vector<Vec3>& r = nodes[k];
    for (std::size_t node = 1; node < r.size(); ++node) {
      if (seabed.Below(r[node]) < -0.1) {
        line.touchdown_segment = static_cast<int>(node) - 1;
        break;
      }
    }
    const int section = properties.section_of[static_cast<std::size_t>(line.touchdown_segment)];
    line.touchdown = place_of(spec.sections[static_cast<std::size_t>(section)].type);
    lines_.push_back(std::move(line));
  }
  start_ = sim.model().initial_pose;
}

void DesignRecord::Add(simulation::Simulation& sim, const simulation::Sample& sample) {
  if (sample.time < from_) return;
  times_.push_back(sample.time);
  const std::vector<std::vector<double>> segments = sim.SegmentTensions();
  for (std::size_t k = 0; k < lines_.size(); ++k) {
    Line& line = lines_[k];
    line.top_tension.push_back(sample.fairlead_tension[k]);
    const std::vector<double>& s = segments[k];
    line.touchdown_tension.push_back(s[static_cast<std::size_t>(line.touchdown_segment)]);
    line.max_along = std::max(line.max_along, *std::max_element(s.begin(), s.end()));
    line.max_along = std::max(line.max_along, sample.fairlead_tension[k]);
  }
  const double offset =
      std::hypot(sample.pose_true(0) - start_(0), sample.pose_true(1) - start_(1));
  offsets_.push_back(offset);
  if (offset > max_offset_ || times_.size() == 1) {
    max_offset_ = offset;
    time_of_max_offset_ = sample.time;
  }
}

nlohmann::json DesignRecord::Summary() const {
  nlohmann::json lines = nlohmann::json::array();
  for (std::size_t k = 0; k < lines_.size(); ++k) {
    const Line& line = lines_[k];
    const std::vector<double>& top = line.top_tension;
    nlohmann::json j;
    j["line"] = k + 1;
    j["type"] = line.top.type;
    j["minimum_breaking_load"] = NumberOrNull(
        line.top.breaking > 0.0 ? std::optional<double>(line.top.breaking) : std::nullopt);
    if (!top.empty()) {
      const auto largest = std::max_element(top.begin(), top.end());
      const Moments moments = MomentsOf(top);
      std::optional<double> after;
      for (std::size_t i = 0; i < top.size(); ++i) {
        if (times_[i] >= failure_time_) after = std::max(after.value_or(top[i]), top[i]);
      }
      j["max_top_tension"] = *largest;
      j["time_of_max_top_tension"] = times_[static_cast<std::size_t>(largest - top.begin())];
      j["mean_top_tension"] = moments.mean;
      j["std_top_tension"] = moments.std_dev;
      j["top_peaks"] = PeaksFit(top, moments);
      j["max_top_tension_after_failure"] = NumberOrNull(after);
      j["max_tension_along"] = line.max_along;
    }
    j["top_damage"] = NumberOrNull(
        line.top.fatigue ? std::optional<double>(analysis::MinerDamage(top, *line.top.fatigue))
                         : std::nullopt);
    j["touchdown_segment"] = line.touchdown_segment + 1;
    j["touchdown_type"] = line.touchdown.type;
    j["touchdown_damage"] =
        NumberOrNull(line.touchdown.fatigue ? std::optional<double>(analysis::MinerDamage(
                                                  line.touchdown_tension, *line.touchdown.fatigue))
                                            : std::nullopt);
    lines.push_back(j);
  }
  return {{"output_rate", output_rate_},
          {"from", from_},
          {"duration", times_.empty() ? 0.0 : times_.back() - times_.front()},
          {"lines", lines},
          {"max_offset", max_offset_},
          {"time_of_max_offset", time_of_max_offset_},
          {"offset_peaks",
           offsets_.empty() ? nlohmann::json(nullptr) : PeaksFit(offsets_, MomentsOf(offsets_))}};
}

}  // namespace moorsim::runner
