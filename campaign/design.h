// A campaign's design checks (its `design:` and its blocks' `design:`, scenarios/
// campaign.h), from its runs' rows, each holding its run's design record (summary.json's
// "design", runner/design_record.h):
// * extremes: per block, point (a combination of the listed factor values) and line, the
//   storm maxima of its seeds' runs fitted with a Gumbel distribution (analysis/
//   extremes.h): the MPM and a quantile with their intervals, the seeds an MPM within +-5 %
//   needs, the mean tension, and the check of the design tension against the line type's
//   breaking load by the campaign's standard (analysis/design_tension.h). Intact blocks
//   take the whole record's maxima, damaged ones those after simulation.statistics_from,
//   transient ones the maxima after the failure; a damaged or transient point's parted
//   line is left out. The vessel's largest offset likewise, against offset_limit.
// * fatigue: the blocks with a probability (the scatter diagram's sea states): per line,
//   at its top and at its touchdown, the mean damage rate of each state's runs weighted by
//   its probability, as damage per year and as a life in years against service_life
//   times fatigue_factor.
// Every number names the runs it comes from, whose rows hold the command that repeats each.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/campaign.h"

namespace moorsim::simulation {

/// The design checks (above) as JSON; null for a campaign without `design`.
nlohmann::json DesignChecks(const scenarios::Campaign& campaign,
                            const std::vector<nlohmann::json>& rows);

/// Writes DIR/design.json, DIR/design.csv (the extremes) and DIR/fatigue.csv for a
/// campaign with `design` (nothing otherwise).
void WriteDesignTables(const std::filesystem::path& directory, const scenarios::Campaign& campaign,
                       const std::vector<nlohmann::json>& rows);

/// The extremes' and the fatigue's tables as CSV text (a header, a row per entry).
std::string DesignExtremesCsv(const nlohmann::json& checks);
std::string DesignFatigueCsv(const nlohmann::json& checks);

}  // namespace moorsim::simulation
