#include "scenarios/campaign.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <tuple>
#include <utility>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "core/random.h"
#include "scenarios/strict_yaml.h"

namespace moorsim::scenarios {
namespace {

using namespace strict_yaml;  // NOLINT(google-build-using-namespace): the shared reader

// A campaign lists at most this many runs: far beyond a campaign that finishes, small
// enough that a typo (seeds: 1e9) is caught before anything runs.
constexpr std::int64_t kMaxRuns = 10'000'000;
constexpr std::int64_t kMaxValuesPerFactor = 100'000;

// A factor's value text as a number, if it is one (all of it).
std::optional<double> ParseNumber(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

// A uniform draw in the factor's [low, high).
double Draw(const CampaignFactor& f, RandomStream& stream) {
  return f.low + (f.high - f.low) * stream.Uniform();
}

// Phi, the standard normal distribution function: accurate to the last bits below 0,
// where it is small.
double NormalCdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

// A draw of the normal factor within its [min, max]. While the window holds at least
// kRejectionMass of the probability, draws outside it are drawn again, as campaigns always
// have (so their values stay as they were); a narrower window, which could take millions
// of draws per value, inverts the distribution function restricted to the window instead:
// one uniform draw, whatever the window. Both give the normal law truncated to the window.
double DrawNormal(const CampaignFactor& f, RandomStream& stream) {
  constexpr double kRejectionMass = 0.01;
  constexpr int kMaxRejections = 10'000;  // (1 - 0.01)^10000 < 1e-43: the bound is never met
  const double low = f.min.value_or(-std::numeric_limits<double>::infinity());
  const double high = f.max.value_or(std::numeric_limits<double>::infinity());
  // The window in standard units, mirrored to lie mostly below 0, where Phi is accurate.
  double a = (low - f.mean) / f.std_dev, b = (high - f.mean) / f.std_dev;
  const bool mirrored = a + b > 0.0;
  if (mirrored) std::tie(a, b) = std::pair(-b, -a);
  const double phi_a = NormalCdf(a), phi_b = NormalCdf(b), mass = phi_b - phi_a;
  if (mass >= kRejectionMass) {
    for (int attempt = 0; attempt < kMaxRejections; ++attempt) {
      const double x = f.mean + f.std_dev * stream.Normal();
      if (x >= low && x <= high) return x;
    }
  }
  const double u = stream.Uniform();
  double z = 0.0;
  if (mass <= 1e-9 * phi_b) {
    // So narrow a window that the density is flat across it (to 1e-9).
    z = a + (b - a) * u;
  } else {
    // Phi(z) = Phi(a) + u (Phi(b) - Phi(a)) by bisection, to the last bit of z.
    const double target = phi_a + u * mass;
    double lo = std::max(a, -40.0), hi = std::min(b, 40.0);
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (NormalCdf(mid) < target ? lo : hi) = mid;
    }
    z = 0.5 * (lo + hi);
  }
  return std::clamp(f.mean + f.std_dev * (mirrored ? -z : z), low, high);
}

// The value a run has so far given `key` (factors are made in order).
const std::string& FactorValue(const CampaignRun& run, const std::string& key) {
  for (const auto& [k, value] : run.factors) {
    if (k == key) return value;
  }
  throw ContractError("campaign: factor '" + key + "' has no value yet");
}

// `node` and everything in it in flow style. yaml-cpp emits a parsed node in the style it
// was written in, whatever the emitter is told, so a block list would stay on many lines.
void SetFlowStyle(YAML::Node node) {
  if (!node.IsSequence() && !node.IsMap()) return;
  node.SetStyle(YAML::EmitterStyle::Flow);
  if (node.IsSequence()) {
    for (YAML::Node element : node) SetFlowStyle(element);
  } else {
    for (auto entry : node) SetFlowStyle(entry.second);
  }
}

// A YAML value as `--set` text: a scalar as written, anything else in flow style on one
// line (runs.csv and the commands it lists hold one run per line).
std::string SetText(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  const YAML::Node copy = YAML::Clone(node);
  SetFlowStyle(copy);
  YAML::Emitter out;
  out << copy;
  return out.c_str();
}

bool IsBlockName(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  }
  return true;
}

// Why a campaign may not set or vary the key path `key` to the values `values`, if it may
// not; empty if it may. The path must be written the one way SplitKeyPath takes, so that
// one key never passes as two. `base` is read before any override applies, and every
// run's simulation.seed is the run's seed, from the block's `seeds`.
std::string KeyPathProblem(const std::string& key, const std::vector<YAML::Node>& values,
                           const std::string& example) {
  if (key.find('=') != std::string::npos || key.find(' ') != std::string::npos) {
    return "'" + key + "' is not a key path (e.g. " + example + ")";
  }
  std::vector<KeyStep> steps;
  try {
    steps = SplitKeyPath(key);
  } catch (const InputError& error) {
    return error.what();
  }
  if (steps.front().key == "base") {
    return "'" + key +
           "': a campaign cannot set the scenario's base (it is read before any override); "
           "name another scenario in `scenario:`";
  }
  bool seed = UnderPath(key, "simulation.seed");
  for (const YAML::Node& value : values) {
    seed = seed || (key == "simulation" && value.IsMap() && value["seed"].IsDefined());
  }
  if (seed) {
    return "'" + key +
           "': every run's simulation.seed is its own seed, which would replace this value; "
           "vary seeds with the block's `seeds` (a count or {from: A, to: B})";
  }
  return "";
}

// `set:` as "key=value" texts in the order written. A key path is checked for form here;
// whether it names a scenario key is checked when the runs' scenarios are loaded.
std::vector<std::string> ParseSet(const Reader& r, const YAML::Node& node) {
  std::vector<std::string> set;
  if (!r.IsMap()) r.Fail(r.Text() + " must be a map of key paths to values");
  const std::vector<std::string> keys = r.Keys();
  std::size_t i = 0;
  for (const auto& entry : node) {
    const std::string& key = keys[i++];
    const std::string problem = KeyPathProblem(key, {entry.second}, "simulation.duration");
    if (!problem.empty()) r.FailAtKey(entry.first, problem);
    set.push_back(key + "=" + SetText(entry.second));
  }
  return set;
}

// Integer number of steps from `from` to `to` (inclusive), tolerant of rounding.
std::vector<std::string> ExpandRange(const Reader& r) {
  r.CheckKeys();
  const double from = r.Required<double>("from");
  const double to = r.Required<double>("to");
  const double step = r.Required<double>("step");
  if (!(to >= from))
    r.Child("to").Fail(FormatNumber(to) + " must be >= from (" + FormatNumber(from) + ")");
  const double count = std::floor((to - from) / step * (1.0 + 1e-12) + 1e-9) + 1.0;
  if (count > static_cast<double>(kMaxValuesPerFactor)) {
    r.Fail("gives " + FormatNumber(count) + " values, more than " +
           std::to_string(kMaxValuesPerFactor));
  }
  std::vector<std::string> values;
  for (int i = 0; i < static_cast<int>(count); ++i) {
    // 15 significant digits: 0.1 + 2 * 0.1 reads 0.3, as written by hand.
    values.push_back(Significant(from + i * step, 15));
  }
  return values;
}

// [low, high] with low < high into f.low, f.high; `shape` names what r must be.
void ReadInterval(const Reader& r, const std::string& shape, CampaignFactor& f) {
  const std::vector<Reader> bounds = r.Items();
  if (bounds.size() != 2) r.Fail(r.Text() + " must be " + shape);
  f.low = bounds[0].As<double>();
  f.high = bounds[1].As<double>();
  if (!(f.high > f.low))
    bounds[1].Fail(FormatNumber(f.high) + " must be > low (" + FormatNumber(f.low) + ")");
}

CampaignFactor ParseFactor(const Reader& r, const YAML::Node& node) {
  r.CheckKeys();
  CampaignFactor f;
  f.mark = r.mark();
  f.key = r.Required<std::string>("key");
  std::vector<YAML::Node> values;
  for (const char* kind : {"values", "choice"}) {
    const YAML::Node list = node[kind];
    if (!list.IsDefined() || !list.IsSequence()) continue;
    for (const YAML::Node& value : list) values.push_back(value);
  }
  if (const std::string problem = KeyPathProblem(f.key, values, "failure.line"); !problem.empty()) {
    r.Child("key").Fail(problem);
  }
  int kinds = 0;
  for (const char* k : {"values", "range", "uniform", "normal", "choice", "follows"}) {
    if (r.Find(k)) ++kinds;
  }
  if (kinds != 1) r.Fail("give exactly one of values, range, uniform, normal, choice, follows");
  for (const char* k : {"add", "modulo", "function", "scale"}) {
    if (r.Find(k) && !r.Find("follows")) r.Child(k).Fail(std::string(k) + " goes with follows");
  }
  const auto list = [&](const char* key) {
    const Reader list_reader = r.Child(key);
    const std::vector<Reader> items = list_reader.Items();
    if (items.empty()) list_reader.Fail("an empty list");
    std::vector<std::string> values;
    const YAML::Node list_node = node[key];
    for (std::size_t i = 0; i < items.size(); ++i) {
      items[i].CheckUntagged("the plain value");
      if (list_node[i].IsNull()) items[i].Fail("an empty value");
      values.push_back(SetText(list_node[i]));
    }
    return values;
  };
  if (r.Find("values")) {
    f.kind = CampaignFactor::Kind::kValues;
    f.values = list("values");
  } else if (r.Find("choice")) {
    f.kind = CampaignFactor::Kind::kChoice;
    f.values = list("choice");
  } else if (const std::optional<Reader> range = r.Find("range")) {
    f.kind = CampaignFactor::Kind::kValues;
    f.values = ExpandRange(*range);
  } else if (r.Find("follows")) {
    f.kind = CampaignFactor::Kind::kFollows;
    f.follows = r.Child("follows").As<std::string>();
    if (const std::optional<Reader> add = r.Find("add")) {
      if (!add->IsList()) {
        f.low = f.high = add->As<double>();
      } else {
        ReadInterval(*add, "a number or [low, high]", f);
      }
    }
    if (const std::optional<Reader> modulo = r.Find("modulo")) {
      f.modulo = modulo->As<double>();  // > 0 (the schema)
    }
    if (const std::optional<Reader> function = r.Find("function")) {
      // cos or sin of the followed value in degrees.
      f.function = function->As<CampaignFactor::Function>();
    }
    if (const std::optional<Reader> scale = r.Find("scale")) {
      f.scale = scale->As<double>();
      if (!std::isfinite(f.scale)) scale->Fail(FormatNumber(f.scale) + " must be a finite number");
    }
  } else if (const std::optional<Reader> uniform = r.Find("uniform")) {
    f.kind = CampaignFactor::Kind::kUniform;
    ReadInterval(*uniform, "[low, high]", f);
  } else {
    const Reader normal = *r.Find("normal");
    normal.CheckKeys();
    f.kind = CampaignFactor::Kind::kNormal;
    f.mean = normal.Required<double>("mean");
    f.std_dev = normal.Required<double>("std_dev");
    f.min = normal.Maybe<double>("min");
    f.max = normal.Maybe<double>("max");
    const double low = f.min.value_or(-std::numeric_limits<double>::infinity());
    const double high = f.max.value_or(std::numeric_limits<double>::infinity());
    if (!(high > low))
      normal.Child("max").Fail(FormatNumber(high) + " must be > min (" + FormatNumber(low) + ")");
    // Rejection sampling must end: the window has to hold a fair share of the mass.
    if (std::max(low - f.mean, f.mean - high) > 3.0 * f.std_dev) {
      normal.Fail("[min, max] lies more than 3 standard deviations from the mean");
    }
  }
  return f;
}

// A follows factor takes an earlier factor's value, which must be a number.
void CheckFollows(const Reader& r, std::span<const CampaignFactor> earlier,
                  const std::string& followed) {
  const auto it = std::find_if(earlier.begin(), earlier.end(),
                               [&](const CampaignFactor& f) { return f.key == followed; });
  if (it == earlier.end()) {
    r.Child("follows").Fail("'" + followed + "' is not a factor listed above it in this block");
  }
  for (const std::string& value : it->values) {
    if (!ParseNumber(value)) {
      r.Child("follows").Fail("'" + followed + "' has the value '" + value +
                              "', not a number to add to");
    }
  }
}

CampaignBlock ParseBlock(const Reader& r, const YAML::Node& node) {
  r.CheckKeys();
  CampaignBlock b;
  b.mark = r.mark();
  b.name = r.Required<std::string>("name");
  if (!IsBlockName(b.name)) {
    r.Child("name").Fail("'" + b.name + "' must be letters, digits, '_' or '-'");
  }
  if (const std::optional<Reader> set = r.Find("set")) b.set = ParseSet(*set, node["set"]);
  if (const std::optional<Reader> factors = r.Find("factors")) {
    const std::vector<Reader> items = factors->Items();
    for (std::size_t i = 0; i < items.size(); ++i) {
      b.factors.push_back(ParseFactor(items[i], node["factors"][i]));
      for (std::size_t j = 0; j < i; ++j) {
        const std::string& key = b.factors[i].key;
        const std::string& earlier = b.factors[j].key;
        if (earlier == key) {
          items[i].Child("key").Fail("'" + key + "' is varied twice in this block");
        }
        // One would overwrite the other's value, and its column would show a value the run
        // did not have.
        if (UnderPath(key, earlier) || UnderPath(earlier, key)) {
          items[i].Child("key").Fail("'" + key + "' overlaps '" + earlier +
                                     "', varied above in this block (each value is varied once)");
        }
      }
      if (b.factors[i].kind == CampaignFactor::Kind::kFollows) {
        CheckFollows(items[i], std::span(b.factors).first(i), b.factors[i].follows);
      }
    }
  }
  if (const std::optional<Reader> combine = r.Find("combine")) {
    b.zip = combine->As<CampaignBlock::Combine>() == CampaignBlock::Combine::kZip;
  }
  if (const std::optional<Reader> design = r.Find("design")) {
    design->CheckKeys();
    CampaignBlock::Design d;
    design->Optional("condition", d.condition);
    d.probability = design->Maybe<double>("probability");
    if (d.probability && d.condition != analysis::DesignCondition::kIntact) {
      design->Child("probability").Fail("a fatigue sea state is an intact one (condition: intact)");
    }
    design->Optional("method", d.method);
    if (d.method == analysis::ExtremesMethod::kWeibull) {
      if (d.condition == analysis::DesignCondition::kTransient) {
        design->Child("method").Fail(
            "a transient's maxima come after its failure: fit them over seeds (gumbel)");
      }
      if (d.probability) {
        design->Child("method").Fail("a fatigue sea state has no extremes to fit");
      }
    }
    if (const std::optional<Reader> intact = design->Find("intact")) {
      d.intact = intact->As<std::string>();
      d.intact_mark = intact->mark();
      if (d.condition != analysis::DesignCondition::kTransient) {
        intact->Fail("only a transient block takes its instants from an intact block");
      }
    }
    b.design = d;
  }
  const Reader seeds = r.Child("seeds");
  if (seeds.IsMap()) {
    seeds.CheckKeys();
    b.first_seed = seeds.Required<std::uint64_t>("from");
    b.last_seed = seeds.Required<std::uint64_t>("to");
    if (*b.last_seed < *b.first_seed) {
      seeds.Child("to").Fail(std::to_string(*b.last_seed) + " must be >= from (" +
                             std::to_string(*b.first_seed) + ")");
    }
    if (*b.last_seed - *b.first_seed >= static_cast<std::uint64_t>(kMaxRuns)) {
      seeds.Fail("more than " + std::to_string(kMaxRuns) + " seeds");
    }
  } else {
    const int count = seeds.As<int>();
    if (count < 1 || count > kMaxRuns) {
      seeds.Fail(std::to_string(count) + " must be in [1, " + std::to_string(kMaxRuns) +
                 "] (or {from: A, to: B})");
    }
    b.seed_count = count;
  }
  if (b.design && b.design->method == analysis::ExtremesMethod::kWeibull &&
      b.SeedsPerPoint() != 1) {
    r.Child("design").Child("method").Fail(
        "weibull fits one long run per point: give the block one seed (and its runs the "
        "length the fit needs)");
  }
  return b;
}

// The zip rule needs the factors' positions, so it is checked where they are known.
void CheckZip(const std::string& file, const CampaignBlock& b, const std::string& path) {
  if (!b.zip) return;
  const CampaignFactor* first = nullptr;
  for (const CampaignFactor& f : b.factors) {
    if (f.kind != CampaignFactor::Kind::kValues) continue;
    if (first == nullptr) {
      first = &f;
    } else if (f.values.size() != first->values.size()) {
      ThrowAt(file, f.mark, path,
              "combine: zip needs lists of one length: '" + f.key + "' has " +
                  std::to_string(f.values.size()) + " values, '" + first->key + "' " +
                  std::to_string(first->values.size()));
    }
  }
}

void BlocksOf(const Reader& root, const ParseContext& strict, const YAML::Node& document,
              Campaign& c);

// The value `set` gives `key` last, if any.
std::optional<std::string> SetValue(const std::vector<std::string>& set, const std::string& key) {
  std::optional<std::string> value;
  for (const std::string& item : set) {
    if (item.starts_with(key + "=")) value = item.substr(key.size() + 1);
  }
  return value;
}

const CampaignFactor* FindFactor(const CampaignBlock& b, const std::string& key) {
  for (const CampaignFactor& f : b.factors) {
    if (f.key == key) return &f;
  }
  return nullptr;
}

// A transient block that names its intact block (design.intact) must be matchable run for
// run: the same seeds, the intact block's listed values, the line each run parts.
void CheckTransientBlocks(const Campaign& c) {
  for (std::size_t i = 0; i < c.blocks.size(); ++i) {
    const CampaignBlock& b = c.blocks[i];
    if (!b.TakesIntactInstants()) continue;
    const auto fail = [&](const std::string& what) {
      ThrowAt(c.source_path, b.design->intact_mark, ItemPath("blocks", i) + ".design.intact", what);
    };
    const auto intact = std::find_if(c.blocks.begin(), c.blocks.end(), [&](const CampaignBlock& x) {
      return x.name == b.design->intact;
    });
    if (intact == c.blocks.end())
      fail("'" + b.design->intact + "' is not a block of this campaign");
    if (!intact->design || intact->design->condition != analysis::DesignCondition::kIntact) {
      fail("block '" + intact->name + "' is not an intact one (design: {condition: intact})");
    }
    if (!b.first_seed || !intact->first_seed) {
      fail("runs are matched by seed: give this block and '" + intact->name +
           "' explicit seeds (seeds: {from: A, to: B})");
    }
    if (*b.first_seed < *intact->first_seed || *b.last_seed > *intact->last_seed) {
      fail("seeds " + std::to_string(*b.first_seed) + ".." + std::to_string(*b.last_seed) +
           ": block '" + intact->name + "' has seeds " + std::to_string(*intact->first_seed) +
           ".." + std::to_string(*intact->last_seed) + " only");
    }
    for (const CampaignFactor& f : intact->factors) {
      if (f.kind != CampaignFactor::Kind::kValues) {
        fail("'" + intact->name + "' draws '" + f.key +
             "': runs are matched by listed values (values or range)");
      }
      const CampaignFactor* mine = FindFactor(b, f.key);
      if (mine == nullptr || mine->kind != CampaignFactor::Kind::kValues) {
        fail("'" + intact->name + "' varies '" + f.key + "': list its values in this block too");
      }
      for (const std::string& value : mine->values) {
        if (std::find(f.values.begin(), f.values.end(), value) == f.values.end()) {
          fail("'" + f.key + "' = " + value + ": block '" + intact->name + "' does not list it");
        }
      }
    }
    const CampaignFactor* line = FindFactor(b, "failure.line");
    if ((line == nullptr || line->kind != CampaignFactor::Kind::kValues) &&
        !SetValue(b.set, "failure.line") && !SetValue(c.set, "failure.line")) {
      fail("the line each run parts: give failure.line (set or listed values)");
    }
    if (FindFactor(b, "failure.time") || SetValue(b.set, "failure.time") ||
        SetValue(c.set, "failure.time")) {
      fail("failure.time is set: the runs take it from block '" + intact->name + "'");
    }
  }
}

// `root` collects its errors (every top-level problem, one per block); each block is read
// with `strict`, which stops at the block's first problem (its factors build on each other).
void ParseDocument(const Reader& root, const ParseContext& strict, const YAML::Node& document,
                   Campaign& c, bool need_scenario) {
  root.CheckKeys();
  root.Attempt([&] {
    root.Optional("name", c.name);
    if (!IsBlockName(c.name)) {
      root.Child("name").Fail("'" + c.name + "' must be letters, digits, '_' or '-'");
    }
  });
  root.Attempt([&] {
    const Reader scenario = root.Child("scenario");
    const std::string given = scenario.As<std::string>();
    if (given.empty()) scenario.Fail("an empty path");
    std::filesystem::path resolved(given);
    if (resolved.is_relative()) {
      resolved = std::filesystem::path(c.source_path).parent_path() / resolved;
    }
    c.scenario_path = resolved.lexically_normal().string();
    std::error_code error;
    if (need_scenario && !std::filesystem::is_regular_file(c.scenario_path, error)) {
      scenario.Fail("'" + given + "': no scenario file at " + c.scenario_path);
    }
  });
  c.seed = root.Required<std::uint64_t>("seed");
  root.Attempt([&] {
    if (const std::optional<Reader> set = root.Find("set")) c.set = ParseSet(*set, document["set"]);
  });
  root.Attempt([&] {
    BlocksOf(root, strict, document, c);
    CheckTransientBlocks(c);
  });
  root.Attempt([&] {
    if (const std::optional<Reader> design = root.Find("design")) {
      design->CheckKeys();
      CampaignDesign d;
      design->Optional("standard", d.standard);
      design->Optional("consequence_class", d.consequence_class);
      design->Optional("quantile", d.quantile);
      design->Optional("confidence", d.confidence);
      d.offset_limit = design->Maybe<double>("offset_limit");
      design->Optional("fatigue_factor", d.fatigue_factor);
      design->Optional("service_life", d.service_life);
      design->Optional("storm_duration", d.storm_duration);
      c.design = d;
    }
  });
}

void BlocksOf(const Reader& root, const ParseContext& strict, const YAML::Node& document,
              Campaign& c) {
  const Reader blocks = root.Child("blocks");
  const std::vector<Reader> items = blocks.Items();
  if (items.empty()) blocks.Fail("an empty list (a campaign has at least one block)");
  const schema::Block* block_schema = schema::Campaign().Find("blocks")->block;
  std::int64_t runs = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    root.Attempt([&] {
      const Reader item(strict, document["blocks"][i], ItemPath("blocks", i), items[i].mark(),
                        block_schema);
      CampaignBlock b = ParseBlock(item, document["blocks"][i]);
      CheckZip(c.source_path, b, ItemPath("blocks", i) + ".factors");
      for (const CampaignBlock& earlier : c.blocks) {
        if (earlier.name == b.name)
          items[i].Child("name").Fail("duplicate block name '" + b.name + "'");
      }
      const double block_runs =
          static_cast<double>(b.Points()) * static_cast<double>(b.SeedsPerPoint());
      if (block_runs + static_cast<double>(runs) > static_cast<double>(kMaxRuns)) {
        items[i].Fail("the campaign would have more than " + std::to_string(kMaxRuns) + " runs");
      }
      runs += b.Runs();
      c.blocks.push_back(std::move(b));
    });
  }
}

}  // namespace

std::int64_t CampaignBlock::Points() const {
  std::int64_t points = 1;
  bool any = false;
  for (const CampaignFactor& f : factors) {
    if (f.kind != CampaignFactor::Kind::kValues) continue;
    const auto n = static_cast<std::int64_t>(f.values.size());
    if (zip) {
      points = n;  // equal lengths (checked at load)
    } else {
      // Saturate: the caller compares the product with kMaxRuns.
      points = points > kMaxRuns ? points : points * n;
    }
    any = true;
  }
  return any ? points : 1;
}

std::int64_t CampaignBlock::SeedsPerPoint() const {
  if (first_seed) return static_cast<std::int64_t>(*last_seed - *first_seed) + 1;
  return seed_count;
}

std::int64_t Campaign::NumRuns() const { return FirstRunOf(blocks.size()); }

std::int64_t Campaign::FirstRunOf(std::size_t block) const {
  std::int64_t first = 0;
  for (std::size_t k = 0; k < block; ++k) first += blocks[k].Runs();
  return first;
}

std::vector<std::string> Campaign::FactorKeys() const {
  std::vector<std::string> keys;
  for (const CampaignBlock& b : blocks) {
    for (const CampaignFactor& f : b.factors) {
      if (std::find(keys.begin(), keys.end(), f.key) == keys.end()) keys.push_back(f.key);
    }
  }
  return keys;
}

std::uint64_t DerivedRunSeed(std::uint64_t campaign_seed, std::int64_t index) {
  return SplitMix64Mix(SplitMix64Mix(campaign_seed) ^
                       Fnv1a64("campaign run " + std::to_string(index)));
}

CampaignRun MakeCampaignRun(const Campaign& campaign, std::int64_t index) {
  if (index < 0 || index >= campaign.NumRuns()) {
    throw InputError("run " + std::to_string(index) + ": the campaign has runs 0.." +
                     std::to_string(campaign.NumRuns() - 1));
  }
  CampaignRun run;
  run.index = index;
  std::int64_t offset = index;
  while (true) {
    const CampaignBlock& b = campaign.blocks[static_cast<std::size_t>(run.block)];
    const std::int64_t size = b.Runs();
    if (offset < size) break;
    offset -= size;
    ++run.block;
  }
  const CampaignBlock& b = campaign.blocks[static_cast<std::size_t>(run.block)];
  const std::int64_t seeds = b.SeedsPerPoint();
  const std::int64_t point = offset / seeds;
  const std::int64_t replicate = offset % seeds;
  run.seed = b.first_seed ? *b.first_seed + static_cast<std::uint64_t>(replicate)
                          : DerivedRunSeed(campaign.seed, index);
  // The grid's point index in mixed radix, the last listed factor fastest.
  std::vector<std::int64_t> level(b.factors.size(), 0);
  std::int64_t rest = point;
  for (std::size_t i = b.factors.size(); i-- > 0;) {
    const CampaignFactor& f = b.factors[i];
    if (f.kind != CampaignFactor::Kind::kValues) continue;
    const auto n = static_cast<std::int64_t>(f.values.size());
    level[i] = b.zip ? point : rest % n;
    rest = b.zip ? rest : rest / n;
  }
  for (std::size_t i = 0; i < b.factors.size(); ++i) {
    const CampaignFactor& f = b.factors[i];
    std::string value;
    if (f.kind == CampaignFactor::Kind::kValues) {
      value = f.values[static_cast<std::size_t>(level[i])];
    } else {
      RandomStream stream = RandomStream::Derive(
          campaign.seed, "campaign run " + std::to_string(index) + " factor " + f.key);
      switch (f.kind) {
        case CampaignFactor::Kind::kUniform:
          value = FormatNumber(Draw(f, stream));
          break;
        case CampaignFactor::Kind::kNormal:
          value = FormatNumber(DrawNormal(f, stream));
          break;
        case CampaignFactor::Kind::kChoice: {
          const auto n = f.values.size();
          const auto k = std::min(n - 1, static_cast<std::size_t>(stream.Uniform() * n));
          value = f.values[k];
          break;
        }
        case CampaignFactor::Kind::kFollows: {
          double x = *ParseNumber(FactorValue(run, f.follows));
          if (f.function == CampaignFactor::Function::kCos) x = std::cos(x * kDegree);
          if (f.function == CampaignFactor::Function::kSin) x = std::sin(x * kDegree);
          x = f.scale * x + (f.high > f.low ? Draw(f, stream) : f.low);
          if (f.modulo > 0.0) x -= f.modulo * std::floor(x / f.modulo + 0.5);
          value = FormatNumber(x);
          break;
        }
        case CampaignFactor::Kind::kValues:
          break;
      }
    }
    run.factors.emplace_back(f.key, value);
  }
  run.overrides = campaign.set;
  run.overrides.insert(run.overrides.end(), b.set.begin(), b.set.end());
  for (const auto& [key, value] : run.factors) run.overrides.push_back(key + "=" + value);
  run.overrides.push_back("simulation.seed=" + std::to_string(run.seed));
  return run;
}

std::optional<TransientSource> TransientSourceOf(const Campaign& c, const CampaignRun& run) {
  const CampaignBlock& b = c.blocks[static_cast<std::size_t>(run.block)];
  if (!b.TakesIntactInstants()) return std::nullopt;
  TransientSource source;
  const std::optional<std::string> line = SetValue(run.overrides, "failure.line");
  const char* end = line ? line->data() + line->size() : nullptr;
  if (!line || std::from_chars(line->data(), end, source.line).ptr != end || source.line < 1) {
    throw InputError("failure.line '" + line.value_or("") +
                     "': a transient run parts one line, numbered from 1");
  }
  std::size_t k = 0;
  while (c.blocks[k].name != b.design->intact) ++k;
  const CampaignBlock& intact = c.blocks[k];
  const std::int64_t start = c.FirstRunOf(k);
  const std::int64_t seeds = intact.SeedsPerPoint();
  const auto replicate = static_cast<std::int64_t>(run.seed - *intact.first_seed);
  for (std::int64_t point = 0; point < intact.Points(); ++point) {
    const CampaignRun candidate = MakeCampaignRun(c, start + point * seeds + replicate);
    bool same = true;
    for (const auto& [key, value] : candidate.factors)
      same = same && FactorValue(run, key) == value;
    if (same) {
      source.intact_run = candidate.index;
      return source;
    }
  }
  throw InputError("no run of block '" + intact.name + "' has seed " + std::to_string(run.seed) +
                   " and this run's values of its factors");
}

void SetFailureTime(CampaignRun& run, double time) {
  run.overrides.insert(run.overrides.end() - 1, "failure.time=" + FormatNumber(time));
}

std::string ShellQuote(const std::string& text) {
  bool plain = !text.empty();
  for (const char c : text) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) ||
          std::string_view("_./:=,+-").find(c) != std::string_view::npos)) {
      plain = false;
    }
  }
  if (plain) return text;
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string CampaignRun::Command(const Campaign& campaign, const std::string& out_dir) const {
  std::string command = "moorsim run " + ShellQuote(campaign.scenario_path);
  if (!out_dir.empty()) command += " --out " + ShellQuote(out_dir);
  // Every override but the seed as --set, in order; the seed last, as --seed appends it.
  for (std::size_t i = 0; i + 1 < overrides.size(); ++i) {
    command += " --set " + ShellQuote(overrides[i]);
  }
  return command + " --seed " + std::to_string(seed);
}

Campaign ParseCampaign(const std::string& yaml_text, const std::string& source_name,
                       bool need_scenario) {
  Campaign c;
  c.source_path = source_name;
  c.text = yaml_text;
  c.name = std::filesystem::path(source_name).stem().string();
  std::map<std::string, SourceMark> marks;
  ParseContext strict;
  strict.file = source_name;
  strict.marks = &marks;
  strict.text = &yaml_text;
  std::vector<std::string> errors;
  ParseContext context = strict;
  context.errors = &errors;
  try {
    const YAML::Node document = LoadDocument(yaml_text, source_name, "campaign", "scenario");
    const Reader root(context, document, "", ToSourceMark(document.Mark()), &schema::Campaign());
    ParseDocument(root, strict, document, c, need_scenario);
  } catch (const YAML::Exception& error) {
    ThrowAt(source_name, ToSourceMark(error.mark), "", error.msg);
  }
  ThrowCollected(std::move(errors));
  return c;
}

Campaign LoadCampaign(const std::string& path) {
  constexpr std::size_t kMaxCampaignBytes = 4 << 20;
  return ParseCampaign(ReadInputFile(path, kMaxCampaignBytes, "campaign"), path);
}

}  // namespace moorsim::scenarios
