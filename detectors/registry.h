// The detector registry: one table, sorted by type name, of every detector the scenario's
// `detectors:` list can name, with its factory, its numeric parameters (default, valid
// range, unit, meaning) and a one-line description. The same table gives MakeDetector()'s
// lookup and checks, DetectorTypes(), the "known: ..." lists of the error messages and the
// --help text, so that none of them can name a detector or a parameter the others lack.
//
// Adding a detector: its own file(s) with a Detector subclass, plus one row in the table in
// registry.cc (name, factory, parameter list, description, and the statistic campaigns
// draw its ROC curves from, if it has one); nothing elsewhere names detector types.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "detectors/detector.h"

namespace moorsim::detectors {

/// The values a parameter may take: [min, max] with either end open or infinite, and
/// optionally whole numbers only.
struct ParameterRange {
  double min = 0.0;
  double max = 0.0;  ///< +infinity: no upper bound
  bool min_open = false;
  bool max_open = false;
  bool integer = false;

  bool Contains(double value) const;
  /// The rule as the error messages state it: "in (0, 1]", ">= 0", "an integer in [2, 10000]".
  std::string Describe() const;
};

/// One numeric parameter of a detector type.
struct DetectorParameter {
  std::string_view name;
  /// nullopt: no fixed default; `default_note` says what the detector does when the
  /// parameter is not given (no note: the scenario must give it).
  std::optional<double> default_value;
  std::string_view default_note;
  ParameterRange range;
  std::string_view unit;  ///< "" if dimensionless
  std::string_view description;
};

/// The parameters of one DetectorSpec after the registry's checks: each is the given value
/// or the table's default.
class DetectorParameters {
 public:
  DetectorParameters(std::span<const DetectorParameter> table,
                     const std::map<std::string, double>& given)
      : table_(table), given_(given) {}
  /// The given value, else the default; nullopt if neither (a parameter without default).
  std::optional<double> Find(std::string_view name) const;
  /// Find() for a parameter that has a default (always-on check).
  double Get(std::string_view name) const;
  /// Whether the scenario gave the parameter (not its default).
  bool Given(std::string_view name) const { return given_.contains(std::string(name)); }

 private:
  std::span<const DetectorParameter> table_;
  const std::map<std::string, double>& given_;
};

using DetectorFactory = std::unique_ptr<Detector> (*)(const DetectorParameters&);

/// The scalar statistic a detector type compares with its alarm threshold, for campaigns'
/// ROC curves (false alarms per hour against detection within T): what it is, a grid of
/// thresholds (increasing) and how a verdict's score gives it (NaN while the score has
/// fewer than two entries). A type without one (value null) records no ROC.
struct DetectorStatistic {
  std::string_view description;
  std::span<const double> thresholds;
  double (*value)(std::span<const double> score) = nullptr;
};

/// One row of the registry.
struct DetectorType {
  std::string_view name;  ///< the `type:` the scenario gives
  DetectorFactory make;
  std::span<const DetectorParameter> parameters;  ///< sorted by name
  std::string_view description;                   ///< one line
  DetectorStatistic statistic;                    ///< for ROC curves; value null: none
  std::string_view score_units = "score";         ///< what the verdict's scores measure
};

/// The registry, sorted by name.
std::span<const DetectorType> DetectorTable();

/// The registered type names, sorted: cells, deficit, dht, glr, mle.
std::vector<std::string_view> DetectorTypes();
/// The ROC statistic of a built-in type, or null (a type without one, a plugin's type, an
/// unknown name).
const DetectorStatistic* StatisticOf(std::string_view type);
/// What a type's verdict scores measure, for the outputs' unit attributes: "probability"
/// (dht), ...; "score" for a type that does not say (plugins, unknown names).
std::string_view ScoreUnitsOf(std::string_view type);

/// Builds the detector a scenario entry names: a built-in one, or with `spec.plugin` one
/// from that plugin library (MakePluginDetector()). `key_path` locates the entry in the
/// scenario for the messages ("detectors[2]"). Throws InputError:
///   "<key_path>.type: unknown detector 'x' (known: cells, deficit, dht, glr, mle)"
///   "<key_path>: unknown parameter 'y' for dht (known: floor, hold, prior_intact, threshold)"
///   "<key_path>.floor: 2 must be in (0, 1)"
std::unique_ptr<Detector> MakeDetector(const DetectorSpec& spec, std::string_view key_path);

/// The --help listing: every type with its description and its parameters (default, range,
/// unit, meaning), one per line; then the types of the plugin libraries registered so far.
std::string DetectorHelp();

/// Loads the plugin library at `path` for the rest of the process (`--plugin PATH`): a
/// scenario then names its types by `type:` alone, as built-in ones. Throws InputError
/// "plugin <path>: ..." for a library that does not load (PluginLibrary::Load) or a type
/// that a built-in detector or an earlier registered library already has. Registering the
/// same path twice is one registration. Call before any thread makes detectors.
void RegisterPluginLibrary(const std::string& path);

namespace internal {

/// Reports a broken programmer's contract: throws moorsim::ContractError "<where>: contract
/// violated: <what>", an always-on assert that a run reports as failed instead of aborting
/// the process (a batch of runs goes on).
[[noreturn]] void ContractViolation(std::string_view where, std::string_view what);

/// "a, b, c": the names of a "known: ..." list.
std::string JoinNames(const std::vector<std::string_view>& names);

/// The registry's checks of a scenario entry's parameters against a type's table (sorted by
/// name): unknown names, values out of range and missing required parameters are
/// InputErrors located at `key_path` (the messages of MakeDetector()).
void CheckParameters(const DetectorSpec& spec, std::span<const DetectorParameter> table,
                     std::string_view type, std::string_view key_path);

inline void Require(bool condition, std::string_view where, std::string_view what) {
  if (!condition) [[unlikely]] {
    ContractViolation(where, what);
  }
}

/// The checks every detector makes on a sample: Reset() has run and the evidence has as
/// many hypotheses as it was given (contract) and finite log-likelihoods (else SolverError
/// "<detector>: log-likelihood of hypothesis k is nan at t = ... s").
void CheckEvidence(std::string_view detector, const Evidence& evidence, int hypotheses);

}  // namespace internal

}  // namespace moorsim::detectors
