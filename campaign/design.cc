#include "campaign/design.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "analysis/design_tension.h"
#include "analysis/extremes.h"
#include "core/format.h"
#include "io/csv_table.h"
#include "runner/run.h"

namespace moorsim::simulation {
namespace {

constexpr double kYear = 365.25 * 86400.0;  // [s]

nlohmann::json EstimateJson(const analysis::Estimate& e) {
  return {{"value", e.value}, {"lower", e.lower}, {"upper", e.upper}};
}

// The runs of one point of one block (ok rows only), and what they share.
struct Group {
  const scenarios::CampaignBlock* block = nullptr;
  std::int64_t point = 0;
  nlohmann::json factors;  // the first run's values (the listed ones are the point's)
  int parted_line = 0;     // damaged or transient: the failure's line
  std::vector<const nlohmann::json*> rows;
  int failed = 0;  // runs of the point without a usable record
};

// The storm maxima of `values` fitted, with what the design table shows of them.
nlohmann::json Extreme(const std::vector<double>& maxima, const scenarios::CampaignDesign& d) {
  nlohmann::json j;
  j["runs"] = maxima.size();
  j["method"] = "gumbel";
  if (maxima.size() < 3) {
    j["mpm"] = nullptr;
    j["note"] = "fewer than 3 runs: no fit";
    return j;
  }
  try {
    const analysis::GumbelFit fit = analysis::FitGumbel(maxima, d.confidence);
    j["mpm"] = EstimateJson(fit.Mpm());
    j["quantile"] = EstimateJson(fit.Quantile(d.quantile));
    j["gumbel"] = {{"location", fit.location}, {"scale", fit.scale}};
    j["runs_for_5_percent"] = fit.SamplesFor(0.05);
  } catch (const std::invalid_argument& e) {
    j["mpm"] = nullptr;
    j["note"] = e.what();
  }
  return j;
}

// One long run's peaks (its record's Weibull fit, `fit`, of a `duration` s record) scaled to
// the campaign's storm, with what the design table shows of them.
nlohmann::json ExtremeOfPeaks(const nlohmann::json& fit, double duration,
                              const scenarios::CampaignDesign& d) {
  nlohmann::json j;
  j["runs"] = 1;
  j["method"] = "weibull";
  j["mpm"] = nullptr;
  if (fit.is_null() || !(duration > 0.0)) {
    j["note"] = "fewer than 10 peaks above the mean plus one standard deviation: no fit";
    return j;
  }
  analysis::WeibullFit w;
  w.threshold = fit.at("threshold").get<double>();
  w.location = fit.at("location").get<double>();
  w.scale = fit.at("scale").get<double>();
  w.shape = fit.at("shape").get<double>();
  const std::vector<double> c = fit.at("covariance").get<std::vector<double>>();
  w.covariance << c.at(0), c.at(1), c.at(1), c.at(2);
  w.samples = fit.at("peaks").get<int>();
  w.confidence = d.confidence;
  const double storm_peaks = w.samples * d.storm_duration / duration;
  try {
    j["mpm"] = EstimateJson(w.Mpm(storm_peaks));
    j["quantile"] = EstimateJson(w.Quantile(storm_peaks, d.quantile));
  } catch (const std::invalid_argument& e) {
    j["mpm"] = nullptr;
    j["note"] = e.what();
  }
  j["weibull"] = {{"threshold", w.threshold}, {"location", w.location},
                  {"scale", w.scale},         {"shape", w.shape},
                  {"peaks", w.samples},       {"storm_peaks", storm_peaks}};
  return j;
}

}  // namespace

nlohmann::json DesignChecks(const scenarios::Campaign& campaign,
                            const std::vector<nlohmann::json>& rows) {
  if (!campaign.design) return nullptr;
  const scenarios::CampaignDesign& d = *campaign.design;
  // The run index where each block starts.
  std::map<std::string, std::pair<const scenarios::CampaignBlock*, std::int64_t>> blocks;
  for (std::size_t k = 0; k < campaign.blocks.size(); ++k) {
    blocks[campaign.blocks[k].name] = {&campaign.blocks[k], campaign.FirstRunOf(k)};
  }
  std::map<std::pair<std::string, std::int64_t>, Group> groups;
  std::vector<std::pair<std::string, std::int64_t>> order;
  // In run order, whatever order the rows came in.
  std::vector<const nlohmann::json*> sorted;
  for (const nlohmann::json& row : rows) sorted.push_back(&row);
  std::sort(sorted.begin(), sorted.end(), [](const nlohmann::json* a, const nlohmann::json* b) {
    return a->at("run").get<std::int64_t>() < b->at("run").get<std::int64_t>();
  });
  for (const nlohmann::json* row_pointer : sorted) {
    const nlohmann::json& row = *row_pointer;
    const auto found = blocks.find(row.at("block").get<std::string>());
    if (found == blocks.end() || !found->second.first->design) continue;
    const scenarios::CampaignBlock& block = *found->second.first;
    const std::int64_t point =
        (row.at("run").get<std::int64_t>() - found->second.second) / block.SeedsPerPoint();
    const auto key = std::make_pair(block.name, point);
    Group& g = groups[key];
    if (g.block == nullptr) {
      g.block = &block;
      g.point = point;
      g.factors = row.value("factors", nlohmann::json::object());
      order.push_back(key);
    }
    if (row.value("status", "") != "ok" || !row.contains("design")) {
      ++g.failed;
      continue;
    }
    if (row.at("failure").is_object()) g.parted_line = row.at("failure").at("line").get<int>();
    g.rows.push_back(&row);
  }

  nlohmann::json extremes = nlohmann::json::array();
  nlohmann::json offsets = nlohmann::json::array();
  for (const auto& key : order) {
    const Group& g = groups.at(key);
    const analysis::DesignCondition condition = g.block->design->condition;
    if (g.block->design->probability) continue;  // a fatigue state
    nlohmann::json where = {{"block", g.block->name},
                            {"point", g.point},
                            {"factors", g.factors},
                            {"condition", ChoiceName(condition)},
                            {"failed_runs", g.failed}};
    if (condition != analysis::DesignCondition::kIntact) where["parted_line"] = g.parted_line;
    nlohmann::json runs = nlohmann::json::array();
    for (const nlohmann::json* row : g.rows) runs.push_back(row->at("run"));
    // The storm maxima of the point's runs (Gumbel), or its one run's record of peaks
    // (Weibull), `peaks_of` picking the record's fit.
    const auto extremes_of =
        [&](const std::vector<double>& maxima,
            const std::function<nlohmann::json(const nlohmann::json&)>& peaks_of) {
          if (g.block->design->method == analysis::ExtremesMethod::kWeibull && !g.rows.empty()) {
            const nlohmann::json& record = g.rows.front()->at("design");
            return ExtremeOfPeaks(peaks_of(record), record.at("duration").get<double>(), d);
          }
          return Extreme(maxima, d);
        };
    where["run_indices"] = runs;
    const std::size_t lines = g.rows.empty() ? 0 : g.rows.front()->at("design").at("lines").size();
    for (std::size_t k = 0; k < lines; ++k) {
      if (condition != analysis::DesignCondition::kIntact &&
          static_cast<int>(k) + 1 == g.parted_line) {
        continue;
      }
      std::vector<double> maxima;
      double mean = 0.0;
      for (const nlohmann::json* row : g.rows) {
        const nlohmann::json& line = row->at("design").at("lines").at(k);
        const char* field = condition == analysis::DesignCondition::kTransient
                                ? "max_top_tension_after_failure"
                                : "max_top_tension";
        if (!line.contains(field) || line.at(field).is_null()) continue;
        maxima.push_back(line.at(field).get<double>());
        mean += line.at("mean_top_tension").get<double>();
      }
      nlohmann::json entry = where;
      const nlohmann::json& first_line = g.rows.front()->at("design").at("lines").at(k);
      entry["line"] = k + 1;
      entry["type"] = first_line.at("type");
      entry.update(extremes_of(maxima, [k](const nlohmann::json& record) {
        return record.at("lines").at(k).value("top_peaks", nlohmann::json());
      }));
      entry["mean_tension"] =
          maxima.empty() ? nlohmann::json(nullptr) : nlohmann::json(mean / double(maxima.size()));
      const nlohmann::json mbl = first_line.at("minimum_breaking_load");
      entry["minimum_breaking_load"] = mbl;
      if (entry.at("mpm").is_null() || mbl.is_null()) {
        entry["check"] = nullptr;
        if (mbl.is_null()) entry["note"] = "line type has no minimum_breaking_load";
      } else {
        const analysis::LineExtreme line{.mpm = entry.at("mpm").at("value").get<double>(),
                                         .mean = entry.at("mean_tension").get<double>(),
                                         .mbl = mbl.get<double>()};
        const analysis::DesignCheck c =
            analysis::CheckLine(line, d.standard, condition, d.consequence_class);
        entry["check"] = {
            {"design_tension", c.design_tension}, {"allowed", c.allowed},
            {"safety_factor", c.safety_factor},   {"required_factor", c.required_factor},
            {"utilisation", c.utilisation},       {"pass", c.pass}};
      }
      extremes.push_back(entry);
    }
    std::vector<double> maxima;
    for (const nlohmann::json* row : g.rows) {
      maxima.push_back(row->at("design").at("max_offset").get<double>());
    }
    nlohmann::json offset = where;
    offset.update(extremes_of(maxima, [](const nlohmann::json& record) {
      return record.value("offset_peaks", nlohmann::json());
    }));
    offset["limit"] = d.offset_limit ? nlohmann::json(*d.offset_limit) : nlohmann::json(nullptr);
    offset["pass"] =
        d.offset_limit && !offset.at("mpm").is_null()
            ? nlohmann::json(offset.at("mpm").at("value").get<double>() <= *d.offset_limit)
            : nlohmann::json(nullptr);
    offsets.push_back(offset);
  }

  // Fatigue: the damage rate of each state's runs, weighted by its probability.
  nlohmann::json states = nlohmann::json::array();
  std::map<std::pair<std::size_t, std::string>, double> annual;  // (line, place) -> damage/year
  std::map<std::pair<std::size_t, std::string>, std::string> missing;
  std::map<std::size_t, std::pair<std::string, std::string>> types;  // line -> (top, touchdown)
  double probability = 0.0;
  for (const auto& key : order) {
    const Group& g = groups.at(key);
    if (!g.block->design->probability || g.rows.empty()) continue;
    const double p = *g.block->design->probability;
    probability += p;
    nlohmann::json runs = nlohmann::json::array();
    for (const nlohmann::json* row : g.rows) runs.push_back(row->at("run"));
    states.push_back({{"block", g.block->name},
                      {"point", g.point},
                      {"probability", p},
                      {"runs", g.rows.size()},
                      {"failed_runs", g.failed},
                      {"run_indices", runs}});
    const std::size_t lines = g.rows.front()->at("design").at("lines").size();
    for (std::size_t k = 0; k < lines; ++k) {
      const nlohmann::json& line = g.rows.front()->at("design").at("lines").at(k);
      types[k] = {line.at("type").get<std::string>(), line.at("touchdown_type").get<std::string>()};
      for (const char* place : {"top", "touchdown"}) {
        double rate = 0.0;
        bool known = true;
        for (const nlohmann::json* row : g.rows) {
          const nlohmann::json& design = row->at("design");
          const nlohmann::json& damage =
              design.at("lines").at(k).at(std::string(place) + "_damage");
          const double duration = design.at("duration").get<double>();
          if (damage.is_null() || !(duration > 0.0)) {
            known = false;
            break;
          }
          rate += damage.get<double>() / duration;
        }
        if (!known) {
          missing[{k, place}] = "no T-N curve (fatigue) for its line type";
          continue;
        }
        annual[{k, place}] += p * rate / static_cast<double>(g.rows.size()) * kYear;
      }
    }
  }
  nlohmann::json fatigue_lines = nlohmann::json::array();
  for (const auto& [line, type] : types) {
    nlohmann::json entry = {{"line", line + 1}};
    for (const char* place : {"top", "touchdown"}) {
      nlohmann::json j = {{"type", std::string(place) == "top" ? type.first : type.second}};
      const auto gone = missing.find({line, place});
      if (gone != missing.end()) {
        j["annual_damage"] = nullptr;
        j["life_years"] = nullptr;
        j["pass"] = nullptr;
        j["note"] = gone->second;
      } else {
        const double damage = annual.at({line, place});
        const double life = damage > 0.0 ? 1.0 / damage : INFINITY;
        j["annual_damage"] = damage;
        j["life_years"] = std::isfinite(life) ? nlohmann::json(life) : nlohmann::json(nullptr);
        j["pass"] = life >= d.fatigue_factor * d.service_life;
      }
      entry[place] = j;
    }
    fatigue_lines.push_back(entry);
  }
  return {{"standard", ChoiceName(d.standard)},
          {"consequence_class", d.consequence_class},
          {"quantile", d.quantile},
          {"confidence", d.confidence},
          {"storm_duration", d.storm_duration},
          {"extremes", extremes},
          {"offsets", offsets},
          {"fatigue",
           {{"service_life", d.service_life},
            {"fatigue_factor", d.fatigue_factor},
            {"probability", probability},
            {"states", states},
            {"lines", fatigue_lines}}}};
}

namespace {

std::string Cell(const nlohmann::json& j) {
  if (j.is_null()) return "";
  if (j.is_number()) return FormatNumber(j.get<double>());
  if (j.is_boolean()) return j.get<bool>() ? "pass" : "fail";
  if (j.is_string()) return output::CsvField(j.get<std::string>());
  return output::CsvField(j.dump());
}

const nlohmann::json& At(const nlohmann::json& j, std::initializer_list<const char*> path) {
  static const nlohmann::json kNull;
  const nlohmann::json* at = &j;
  for (const char* key : path) {
    if (!at->is_object() || !at->contains(key)) return kNull;
    at = &at->at(key);
  }
  return *at;
}

}  // namespace

void WriteDesignTables(const std::filesystem::path& directory, const scenarios::Campaign& campaign,
                       const std::vector<nlohmann::json>& rows) {
  if (!campaign.design) return;
  const nlohmann::json checks = DesignChecks(campaign, rows);
  runner::WriteFilesAtomically({{directory / "design.json", checks.dump(2) + "\n"},
                                {directory / "design.csv", DesignExtremesCsv(checks)},
                                {directory / "fatigue.csv", DesignFatigueCsv(checks)}});
}

std::string DesignExtremesCsv(const nlohmann::json& checks) {
  std::ostringstream csv;
  csv << "block,point,condition,parted_line,line,type,runs,method,mpm,mpm_lower,mpm_upper,"
         "quantile,"
         "mean_tension,minimum_breaking_load,design_tension,safety_factor,required_factor,"
         "utilisation,result\n";
  if (checks.is_null()) return csv.str();
  for (const nlohmann::json& e : checks.at("extremes")) {
    csv << Cell(e.at("block")) << ',' << Cell(e.at("point")) << ',' << Cell(e.at("condition"))
        << ',' << Cell(At(e, {"parted_line"})) << ',' << Cell(e.at("line")) << ','
        << Cell(e.at("type")) << ',' << Cell(e.at("runs")) << ',' << Cell(e.at("method")) << ','
        << Cell(At(e, {"mpm", "value"})) << ',' << Cell(At(e, {"mpm", "lower"})) << ','
        << Cell(At(e, {"mpm", "upper"})) << ',' << Cell(At(e, {"quantile", "value"})) << ','
        << Cell(e.at("mean_tension")) << ',' << Cell(e.at("minimum_breaking_load")) << ','
        << Cell(At(e, {"check", "design_tension"})) << ','
        << Cell(At(e, {"check", "safety_factor"})) << ','
        << Cell(At(e, {"check", "required_factor"})) << ',' << Cell(At(e, {"check", "utilisation"}))
        << ',' << Cell(At(e, {"check", "pass"})) << '\n';
  }
  return csv.str();
}

std::string DesignFatigueCsv(const nlohmann::json& checks) {
  std::ostringstream csv;
  csv << "line,place,type,annual_damage,life_years,result\n";
  if (checks.is_null()) return csv.str();
  for (const nlohmann::json& line : checks.at("fatigue").at("lines")) {
    for (const char* place : {"top", "touchdown"}) {
      const nlohmann::json& p = line.at(place);
      csv << Cell(line.at("line")) << ',' << place << ',' << Cell(p.at("type")) << ','
          << Cell(p.at("annual_damage")) << ',' << Cell(p.at("life_years")) << ','
          << Cell(p.at("pass")) << '\n';
    }
  }
  return csv.str();
}

}  // namespace moorsim::simulation
