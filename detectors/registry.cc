#include "detectors/registry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/types.h"
#include "detectors/cells.h"
#include "detectors/deficit.h"
#include "detectors/dht.h"
#include "detectors/fused.h"
#include "detectors/glr.h"
#include "detectors/mle.h"
#include "detectors/plugin_detector.h"

namespace moorsim::detectors {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The ranges the detectors use.
constexpr ParameterRange kProbability{0.0, 1.0, true, true, false};          // (0, 1)
constexpr ParameterRange kUpToOne{0.0, 1.0, true, false, false};             // (0, 1]
constexpr ParameterRange kNonNegative{0.0, kInfinity, false, false, false};  // >= 0
constexpr ParameterRange kPositive{0.0, kInfinity, true, false, false};      // > 0
constexpr ParameterRange kWindow{2.0, 10000.0, false, false, true};          // [2, 10000]

// Each detector's parameters, sorted by name; the defaults are the options structs',
// except the GLR's threshold and hold: GlrOptions' library default is the white-residual
// chi-square threshold, while a scenario's GLR watches an observer on the coupled plant,
// whose residuals carry the slowly varying wave drift. On the thesis plant (seeds 1-3,
// 8 lines + 3600 s without failure each) the nominal filter's g reached 166-511 without
// any failure and 130 just before a break; h = 120 held 15 s missed 2 of 24 isolations
// and gave 2 false alarms, the chi-square 38.7 held 0 s gave dozens (benchmarks/README.md).
constexpr double kGlrThreshold = 120.0;
constexpr double kGlrHold = 15.0;
constexpr ParameterRange kCount{1.0, 10000.0, false, false, true};  // [1, 10000]
constexpr ParameterRange kDelay{0.0, 10000.0, false, false, true};  // [0, 10000]
constexpr ParameterRange kSwitch{0.0, 1.0, false, false, true};     // 0 or 1

// The cells test's parameters; the fused detector takes the same with its own defaults.
constexpr std::array<DetectorParameter, 10> CellsParameters(const CellsOptions& d) {
  return {{
      {"anchor_fall", d.anchor_fall, "", kNonNegative, "",
       "a cell reading over half its expectation confirms only while its mean ratio is this much "
       "below its highest of the low spell (0: off)"},
      {"confirm", 1.0, "", kSwitch, "",
       "1: the intact filter's bias must show the lost load before the alarm; 0: cells alone"},
      {"confirm_floor", d.confirm_floor, "", kNonNegative, "N",
       "least bias shift toward the lost line that confirms"},
      {"confirm_fraction", d.confirm_fraction, "", kNonNegative, "",
       "share of the horizontal load the cell says is lost that the bias must show"},
      {"confirm_hold", d.confirm_hold, "", kNonNegative, "s",
       "how long the bias must keep showing the lost load before it confirms"},
      {"confirm_time", d.confirm_time, "", kPositive, "s",
       "how long a low cell waits for the pose before it is declared faulty"},
      {"drop", d.drop, "", kProbability, "",
       "fraction of its expected reading a cell must lose to read low"},
      {"fall_time", d.fall_time, "", kNonNegative, "s",
       "a low cell counts only if it read true this long before (a fall, not a drift; 0: off)"},
      {"hold", d.hold, "", kNonNegative, "s", "time a cell must read low before the alarm"},
      {"window", d.window, "", kCount, "samples",
       "samples in the moving mean of reading / expected"},
  }};
}
constexpr std::array<DetectorParameter, 10> kCellsParameters = CellsParameters(CellsOptions{});
constexpr std::array<DetectorParameter, 10> kFusedParameters =
    CellsParameters(FusedOptions{}.cells);

constexpr std::array<DetectorParameter, 20> kDeficitParameters = {{
    {"baseline_time", DeficitOptions{}.baseline_time, "", kPositive, "s",
     "time constant of the learned baseline and disturbance of the intact filter's bias"},
    {"confirm", DeficitOptions{}.confirm, "", kNonNegative, "nats",
     "two-stage verdict (0: off): a fast test's alarm stands once this test's evidence for "
     "its line reaches this"},
    {"confirm_time", DeficitOptions{}.confirm_time, "", kPositive, "s",
     "how long a fast alarm waits for confirmation before the fast test starts over"},
    {"direction_prior", DeficitOptions{}.direction_prior, "", kNonNegative, "",
     "independent values the energy-only drift regression is worth as the prior of "
     "drift_direction's three gains"},
    {"drift", 1.0, "", kSwitch, "",
     "1: the baseline follows the estimated wave motion's energy (slowly varying drift); 0: "
     "constant"},
    {"drift_direction", DeficitOptions{}.drift_direction ? 1.0 : 0.0, "", kSwitch, "",
     "1: the drift regression takes the wave motion's direction (x^2, y^2, xy); 0: its "
     "energy x^2 + y^2 alone"},
    {"fast_lead", DeficitOptions{}.fast_lead, "", kNonNegative, "s",
     "the fast test's lead (with confirm > 0)"},
    {"fast_window", DeficitOptions{}.fast_window, "", kCount, "samples",
     "the fast test's window (with confirm > 0)"},
    {"floor", DeficitOptions{}.floor, "", kPositive, "N",
     "least disturbance standard deviation, added to the learned one"},
    {"lead", DeficitOptions{}.lead, "", kNonNegative, "s",
     "T of the lead compensation b + T db/dt that undoes the intact filter's bias lag"},
    {"learn_delay", DeficitOptions{}.learn_delay, "", kDelay, "samples",
     "age at which a bias sample is learned (held if an alarm is raised first; see relearn)"},
    {"min_fraction", DeficitOptions{}.min_fraction, "", kUpToOne, "",
     "least share of a line's load whose loss is tested (1: the whole load; below, the share "
     "is estimated)"},
    {"relearn", DeficitOptions{}.relearn ? 1.0 : 0.0, "", kSwitch, "",
     "1: an alarm that ends on reversed evidence hands the samples held while it stood to the "
     "learned disturbance; 0: they are dropped"},
    {"release", DeficitOptions{}.release, "", kPositive, "nats",
     "cumulative evidence for no change over the named line that ends the alarm"},
    {"revision", DeficitOptions{}.revision, "", kPositive, "nats",
     "cumulative evidence for another line over the named one that revises the alarm"},
    {"small_sample", DeficitOptions{}.small_sample, "", kNonNegative, "",
     "c: the learned disturbance is used as C (1 + c / n), n the independent values learned"},
    {"threshold", DeficitOptions{}.threshold, "", kPositive, "nats",
     "cumulative evidence for a line's missing load over no change that raises the alarm"},
    {"warmup", DeficitOptions{}.warmup, "", kNonNegative, "s",
     "load evidence learned before any alarm"},
    {"warmup_learning", DeficitOptions{}.warmup_learning ? 1.0 : 0.0, "", kSwitch, "",
     "1: the warm-up's samples are learned at once (the mooring taken as intact); 0: after "
     "learn_delay like the others"},
    {"window", DeficitOptions{}.window, "", kCount, "samples",
     "samples of the bias averaged before the test"},
}};

constexpr std::array<DetectorParameter, 4> kDhtParameters = {{
    {"floor", DhtOptions{}.floor, "", kProbability, "",
     "probability floor p_min (TAPM thesis: 1e-9); hypotheses x floor must be < 1"},
    {"hold", DhtOptions{}.hold, "", kNonNegative, "s",
     "time the same failure hypothesis must stay >= threshold before the alarm"},
    {"prior_intact", std::nullopt, "uniform 1/N", kProbability, "",
     "prior probability of the intact hypothesis; the failures share the rest"},
    {"threshold", DhtOptions{}.threshold, "", kProbability, "",
     "posterior a failure hypothesis must reach for the alarm"},
}};

constexpr std::array<DetectorParameter, 4> kGlrParameters = {{
    {"false_alarm_probability", std::nullopt, "unset (threshold used)", kProbability, "",
     "instead of threshold: h = chi-square(3) quantile at this per-sample probability / "
     "window (white residuals)"},
    {"hold", kGlrHold, "", kNonNegative, "s",
     "time the statistic g must stay above the threshold before the alarm"},
    {"threshold", kGlrThreshold, "", kPositive, "",
     "alarm threshold h on the mean-change statistic g (tuned on the thesis plant, whose "
     "residuals are coloured by wave drift)"},
    {"window", GlrOptions{}.window, "", kWindow, "samples",
     "M, the change times searched (Lajic et al. 2009: 50)"},
}};

constexpr std::array<DetectorParameter, 3> kMleParameters = {{
    {"forgetting_factor", MleOptions{}.forgetting_factor, "", kUpToOne, "",
     "lambda: J <- lambda J - log-likelihood (TAPM thesis: 0.999); memory 1/(1 - lambda) samples"},
    {"hold", MleOptions{}.hold, "", kNonNegative, "s",
     "time a failure hypothesis must have been the argmin before the alarm"},
    {"margin", MleOptions{}.margin, "", kNonNegative, "nats",
     "lead J_0 - J_k the failure hypothesis needs over the intact one for the alarm"},
}};

CellsOptions ReadCellsOptions(const DetectorParameters& p) {
  CellsOptions options;
  options.anchor_fall = p.Get("anchor_fall");
  options.confirm = p.Get("confirm") != 0.0;
  options.confirm_floor = p.Get("confirm_floor");
  options.confirm_fraction = p.Get("confirm_fraction");
  options.confirm_time = p.Get("confirm_time");
  options.confirm_hold = p.Get("confirm_hold");
  options.drop = p.Get("drop");
  options.fall_time = p.Get("fall_time");
  options.hold = p.Get("hold");
  options.window = static_cast<int>(p.Get("window"));
  return options;
}

std::unique_ptr<Detector> MakeCells(const DetectorParameters& p) {
  return std::make_unique<Cells>(ReadCellsOptions(p));
}

std::unique_ptr<Detector> MakeFused(const DetectorParameters& p) {
  return std::make_unique<Fused>(
      FusedOptions{.cells = ReadCellsOptions(p), .pose = {}, .agreement = {}});
}

std::unique_ptr<Detector> MakeDeficit(const DetectorParameters& p) {
  DeficitOptions options;
  options.baseline_time = p.Get("baseline_time");
  options.confirm = p.Get("confirm");
  options.confirm_time = p.Get("confirm_time");
  options.drift = p.Get("drift") != 0.0;
  options.drift_direction = p.Get("drift_direction") != 0.0;
  options.direction_prior = p.Get("direction_prior");
  options.fast_lead = p.Get("fast_lead");
  options.fast_window = static_cast<int>(p.Get("fast_window"));
  options.floor = p.Get("floor");
  options.lead = p.Get("lead");
  options.learn_delay = static_cast<int>(p.Get("learn_delay"));
  options.min_fraction = p.Get("min_fraction");
  options.relearn = p.Get("relearn") != 0.0;
  options.release = p.Get("release");
  options.revision = p.Get("revision");
  options.small_sample = p.Get("small_sample");
  options.threshold = p.Get("threshold");
  options.warmup = p.Get("warmup");
  options.warmup_learning = p.Get("warmup_learning") != 0.0;
  options.window = static_cast<int>(p.Get("window"));
  return std::make_unique<Deficit>(options);
}

std::unique_ptr<Detector> MakeDht(const DetectorParameters& p) {
  DhtOptions options;
  options.floor = p.Get("floor");
  options.hold = p.Get("hold");
  options.prior_intact = p.Find("prior_intact");
  options.threshold = p.Get("threshold");
  return std::make_unique<Dht>(options);
}

std::unique_ptr<Detector> MakeGlr(const DetectorParameters& p) {
  GlrOptions options;
  if (p.Given("false_alarm_probability")) {
    if (p.Given("threshold")) {
      throw InputError("give threshold or false_alarm_probability, not both");
    }
    options.false_alarm_probability = p.Get("false_alarm_probability");
  } else {
    options.threshold = p.Get("threshold");
  }
  options.hold = p.Get("hold");
  options.window = static_cast<int>(p.Get("window"));
  return std::make_unique<Glr>(options);
}

std::unique_ptr<Detector> MakeMle(const DetectorParameters& p) {
  MleOptions options;
  options.forgetting_factor = p.Get("forgetting_factor");
  options.hold = p.Get("hold");
  options.margin = p.Get("margin");
  return std::make_unique<Mle>(options);
}

// The ROC statistics: each detector's score read the way its alarm rule reads it.
constexpr double kDhtThresholds[] = {0.5,   0.6,   0.7,   0.8,    0.9,    0.95,    0.98,    0.99,
                                     0.995, 0.998, 0.999, 0.9995, 0.9999, 0.99999, 0.999999};
constexpr double kMleThresholds[] = {0,  1,  2,  3,  4,  5,  6,  8,   10, 12,
                                     15, 20, 25, 30, 40, 50, 75, 100, 150};
constexpr double kGlrThresholds[] = {10, 12,  15,  18,  22,  27,  33,  39,  47,  56,  68,
                                     82, 100, 120, 150, 180, 220, 270, 330, 390, 470, 560};

// DHT: the largest posterior of a failure hypothesis, max_k>=1 h_k.
double DhtStatistic(std::span<const double> score) {
  if (score.size() < 2) return kNaN;
  return *std::max_element(score.begin() + 1, score.end());
}
// MLE: the best failure hypothesis's lead over intact, max_k>=1 (J_0 - J_k).
double MleStatistic(std::span<const double> score) {
  if (score.size() < 2) return kNaN;
  return score[0] - *std::min_element(score.begin() + 1, score.end());
}
// GLR: the mean-change statistic g, score[0].
double GlrStatistic(std::span<const double> score) {
  if (score.size() < 2) return kNaN;
  return score[0];
}

// The registry, sorted by name.
constexpr std::array<DetectorType, 6> kDetectors = {{
    {"cells",
     MakeCells,
     kCellsParameters,
     "fairlead load cells against the intact model at the filter's pose; a low cell names "
     "its line once the vessel's bias shows the lost load, else it is a faulty cell",
     {}},
    {"deficit",
     MakeDeficit,
     kDeficitParameters,
     "force deficit: CUSUM of the intact filter's bias shift against each line's missing "
     "load, over a learned disturbance; latched until the evidence reverses",
     {}},
    {"dht",
     MakeDht,
     kDhtParameters,
     "dynamic hypothesis testing: floored Bayesian posterior of every hypothesis (Hassani et al. "
     "2018, eq. 47/51)",
     {"largest posterior probability of a failure hypothesis, max_k>=1 h_k", kDhtThresholds,
      DhtStatistic},
     "probability"},
    {"fused",
     MakeFused,
     kFusedParameters,
     "load cells and the pose checking each other, with the sensors judged: a confirmed low "
     "cell names its line; the force-deficit test speaks for a line whose cell cannot; "
     "faulty sensors are named as such (parameters: the cells test's; confirm_time 60 s)",
     {}},
    {"glr",
     MakeGlr,
     kGlrParameters,
     "windowed GLR on the intact model's whitened innovations: mean change detects, known "
     "signatures isolate (Lajic et al. 2009, eq. 21/22)",
     {"GLR mean-change statistic g (chi-square scaled)", kGlrThresholds, GlrStatistic},
     "chi-square statistic"},
    {"mle",
     MakeMle,
     kMleParameters,
     "maximum likelihood: negative log-likelihood with forgetting, argmin (TAPM thesis eq. "
     "4.10)",
     {"lead of the best failure hypothesis over intact, max_k>=1 (J_0 - J_k) [nats]",
      kMleThresholds, MleStatistic},
     "nats (negative log-likelihood)"},
}};

constexpr bool SortedByName(std::span<const DetectorParameter> parameters) {
  for (std::size_t i = 1; i < parameters.size(); ++i) {
    if (!(parameters[i - 1].name < parameters[i].name)) return false;
  }
  return true;
}

constexpr bool TableSorted() {
  for (std::size_t i = 0; i < kDetectors.size(); ++i) {
    if (i > 0 && !(kDetectors[i - 1].name < kDetectors[i].name)) return false;
    if (!SortedByName(kDetectors[i].parameters)) return false;
  }
  return true;
}

static_assert(TableSorted(), "kDetectors and every parameter list must be sorted by name");

const DetectorParameter* FindParameter(std::span<const DetectorParameter> table,
                                       std::string_view name) {
  const auto it = std::lower_bound(
      table.begin(), table.end(), name,
      [](const DetectorParameter& entry, std::string_view key) { return entry.name < key; });
  return it != table.end() && it->name == name ? &*it : nullptr;
}

}  // namespace

bool ParameterRange::Contains(double value) const {
  if (!std::isfinite(value)) return false;
  if (min_open ? !(value > min) : !(value >= min)) return false;
  if (max_open ? !(value < max) : !(value <= max)) return false;
  return !integer || std::floor(value) == value;
}

std::string ParameterRange::Describe() const {
  std::string text = integer ? "an integer " : "";
  if (std::isinf(max)) return text + (min_open ? "> " : ">= ") + FormatNumber(min);
  return text + "in " + (min_open ? "(" : "[") + FormatNumber(min) + ", " + FormatNumber(max) +
         (max_open ? ")" : "]");
}

std::optional<double> DetectorParameters::Find(std::string_view name) const {
  const DetectorParameter* parameter = FindParameter(table_, name);
  internal::Require(parameter != nullptr, "DetectorParameters::Find", "a parameter of the table");
  const auto it = given_.find(std::string(name));
  if (it != given_.end()) return it->second;
  return parameter->default_value;
}

double DetectorParameters::Get(std::string_view name) const {
  const std::optional<double> value = Find(name);
  internal::Require(value.has_value(), "DetectorParameters::Get", "a parameter with a default");
  return *value;
}

std::span<const DetectorType> DetectorTable() { return kDetectors; }

std::vector<std::string_view> DetectorTypes() {
  std::vector<std::string_view> names;
  for (const DetectorType& type : kDetectors) names.push_back(type.name);
  return names;
}

const DetectorStatistic* StatisticOf(std::string_view type) {
  for (const DetectorType& row : kDetectors) {
    if (row.name == type) return row.statistic.value != nullptr ? &row.statistic : nullptr;
  }
  return nullptr;
}

std::string_view ScoreUnitsOf(std::string_view type) {
  for (const DetectorType& row : kDetectors) {
    if (row.name == type) return row.score_units;
  }
  return "score";
}

std::unique_ptr<Detector> MakeDetector(const DetectorSpec& spec, std::string_view key_path) {
  if (!spec.plugin.empty()) return MakePluginDetector(spec.plugin, spec, key_path);
  const std::string path(key_path);
  const auto it = std::lower_bound(
      kDetectors.begin(), kDetectors.end(), spec.type,
      [](const DetectorType& entry, const std::string& name) { return entry.name < name; });
  if (it == kDetectors.end() || it->name != spec.type) {
    if (const std::shared_ptr<const PluginLibrary> library = RegisteredPluginFor(spec.type)) {
      return MakePluginDetector(library->path(), spec, key_path);
    }
    std::vector<std::string_view> known = DetectorTypes();
    const std::vector<std::shared_ptr<const PluginLibrary>> plugins = RegisteredPluginLibraries();
    for (const std::shared_ptr<const PluginLibrary>& library : plugins) {
      for (std::string_view type : library->TypeNames()) known.push_back(type);
    }
    throw InputError(path + ".type: unknown detector '" + spec.type +
                     "' (known: " + internal::JoinNames(known) + ")");
  }
  internal::CheckParameters(spec, it->parameters, it->name, path);
  try {
    return it->make(DetectorParameters(it->parameters, spec.parameters));
  } catch (const InputError& error) {  // a rule between parameters
    throw InputError(path + ": " + error.what());
  }
}

namespace {

void ParameterHelp(std::ostringstream& out, std::span<const DetectorParameter> parameters) {
  for (const DetectorParameter& p : parameters) {
    const std::string default_text =
        p.default_value ? FormatNumber(*p.default_value) : std::string(p.default_note);
    out << "    " << std::left << std::setw(24) << p.name << " default " << default_text
        << (p.unit.empty() || !p.default_value ? "" : " ") << (p.default_value ? p.unit : "")
        << "; " << p.range.Describe() << "; " << p.description << "\n";
  }
}

}  // namespace

std::string DetectorHelp() {
  std::ostringstream out;
  out << "Detectors (the scenario's `detectors:` list: type, optional label, parameters):\n";
  for (const DetectorType& type : kDetectors) {
    out << "  " << type.name << ": " << type.description << "\n";
    ParameterHelp(out, type.parameters);
  }
  for (const std::shared_ptr<const PluginLibrary>& library : RegisteredPluginLibraries()) {
    out << "From plugin " << library->path() << ":\n";
    for (std::string_view type : library->TypeNames()) {
      const char* description = library->Find(type)->description;
      out << "  " << type << ": " << (description != nullptr ? description : "") << "\n";
      ParameterHelp(out, library->Parameters(type));
    }
  }
  return out.str();
}

namespace internal {

std::string JoinNames(const std::vector<std::string_view>& names) {
  std::string joined;
  for (std::string_view name : names) joined += (joined.empty() ? "" : ", ") + std::string(name);
  return joined;
}

void CheckParameters(const DetectorSpec& spec, std::span<const DetectorParameter> table,
                     std::string_view type, std::string_view key_path) {
  const std::string path(key_path);
  for (const auto& [name, value] : spec.parameters) {
    const DetectorParameter* parameter = FindParameter(table, name);
    if (parameter == nullptr) {
      std::vector<std::string_view> known;
      for (const DetectorParameter& p : table) known.push_back(p.name);
      throw InputError(path + ": unknown parameter '" + name + "' for " + std::string(type) +
                       " (known: " + internal::JoinNames(known) + ")");
    }
    if (!parameter->range.Contains(value)) {
      throw InputError(path + "." + name + ": " + FormatNumber(value) + " must be " +
                       parameter->range.Describe());
    }
  }
  for (const DetectorParameter& parameter : table) {
    const bool required = !parameter.default_value && parameter.default_note.empty();
    if (required && !spec.parameters.contains(std::string(parameter.name))) {
      throw InputError(path + ": " + std::string(type) + " needs parameter '" +
                       std::string(parameter.name) + "' (no default)");
    }
  }
}

void ContractViolation(std::string_view where, std::string_view what) {
  throw ContractError(std::string(where) + ": contract violated: " + std::string(what));
}

void CheckEvidence(std::string_view detector, const Evidence& evidence, int hypotheses) {
  Require(hypotheses >= 1, detector, "Reset() before the first sample");
  Require(static_cast<int>(evidence.hypotheses.size()) == hypotheses, detector,
          "evidence for as many hypotheses as Reset() was given");
  for (std::size_t k = 0; k < evidence.hypotheses.size(); ++k) {
    const double value = evidence.hypotheses[k].log_likelihood;
    if (!std::isfinite(value)) {
      std::ostringstream message;
      message << detector << ": log-likelihood of hypothesis " << k << " is " << value
              << " at t = " << evidence.t << " s";
      throw SolverError(message.str());
    }
  }
}

}  // namespace internal

}  // namespace moorsim::detectors
