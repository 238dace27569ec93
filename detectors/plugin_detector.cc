#include "detectors/plugin_detector.h"

#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <mutex>
#include <sstream>

#include "core/error.h"
#include "core/sha256.h"

namespace moorsim::detectors {

namespace {

constexpr std::size_t kErrorSize = 512;

std::string_view Text(const char* text) { return text == nullptr ? std::string_view() : text; }

// The plugin's reason, or `fallback` if it wrote none.
std::string Reason(const char* error, std::string_view fallback) {
  const std::string_view reason = Text(error);
  return reason.empty() ? std::string(fallback) : std::string(reason);
}

class PluginDetector final : public Detector {
 public:
  PluginDetector(std::shared_ptr<const PluginLibrary> library, const moorsim_detector_plugin* type,
                 void* instance)
      : library_(std::move(library)),
        type_(type),
        instance_(instance),
        where_("plugin " + library_->path() + " detector '" + std::string(type_->type) + "'") {}
  ~PluginDetector() override { type_->destroy(instance_); }
  PluginDetector(const PluginDetector&) = delete;
  PluginDetector& operator=(const PluginDetector&) = delete;

  std::string_view type() const override { return type_->type; }
  bool NeedsLoadEvidence() const override { return type_->needs_load_evidence != 0; }

  void SetFailedLines(std::vector<std::array<int, 2>> failed) { failed_ = std::move(failed); }
  const std::shared_ptr<const PluginLibrary>& library() const { return library_; }

  void Reset(int hypotheses) override {
    internal::Require(hypotheses >= 1, where_, "at least one hypothesis");
    hypotheses_ = hypotheses;
    score_.assign(static_cast<std::size_t>(hypotheses), 0.0);
    // The map the bank gave, or moorsim's numbering without pairs: hypothesis h, line h.
    std::vector<int> failed(2 * static_cast<std::size_t>(hypotheses), 0);
    if (failed_.size() == static_cast<std::size_t>(hypotheses)) {
      for (int h = 0; h < hypotheses; ++h) {
        failed[2 * h] = failed_[h][0];
        failed[2 * h + 1] = failed_[h][1];
      }
    } else {
      internal::Require(failed_.empty(), where_, "one failed-lines entry per hypothesis");
      for (int h = 1; h < hypotheses; ++h) failed[2 * h] = h;
    }
    error_[0] = '\0';
    if (type_->reset(instance_, hypotheses, failed.data(), error_, kErrorSize) != 0) {
      throw SolverError(where_ + ": reset failed: " + Reason(error_, "no reason given"));
    }
  }

  Verdict Update(const Evidence& evidence) override {
    internal::CheckEvidence(where_, evidence, hypotheses_);
    const std::size_t n = evidence.hypotheses.size();
    hypothesis_.resize(n);
    for (std::size_t h = 0; h < n; ++h) Convert(evidence.hypotheses[h], hypothesis_[h]);
    moorsim_hypothesis_evidence nominal{};
    if (evidence.nominal) Convert(*evidence.nominal, nominal);
    moorsim_load_evidence load{};
    if (evidence.load) {
      internal::Require(evidence.load->line_load.size() == n, where_,
                        "one line load per hypothesis");
      line_load_.resize(3 * n);
      for (std::size_t h = 0; h < n; ++h) {
        for (int i = 0; i < 3; ++i) line_load_[3 * h + i] = evidence.load->line_load[h](i);
      }
      Copy(evidence.load->bias, load.bias);
      CopyMatrix(evidence.load->bias_covariance, load.bias_covariance);
      load.line_load = line_load_.data();
      Copy(evidence.load->wave_motion, load.wave_motion);
    }
    const moorsim_evidence sample{evidence.t, hypotheses_, hypothesis_.data(),
                                  evidence.nominal ? &nominal : nullptr,
                                  evidence.load ? &load : nullptr};
    std::fill(score_.begin(), score_.end(), 0.0);
    moorsim_verdict verdict{score_.data(), 0, 0};
    error_[0] = '\0';
    if (type_->step(instance_, &sample, &verdict, error_, kErrorSize) != 0) {
      std::ostringstream message;
      message << where_ << ": step failed at t = " << evidence.t
              << " s: " << Reason(error_, "no reason given");
      throw SolverError(message.str());
    }
    // The plugin's side of the contract.
    for (std::size_t h = 0; h < score_.size(); ++h) {
      if (!std::isfinite(score_[h])) {
        std::ostringstream message;
        message << "score of hypothesis " << h << " is " << score_[h] << " at t = " << evidence.t
                << " s";
        internal::ContractViolation(where_, message.str());
      }
    }
    if (verdict.hypothesis < 0 || verdict.hypothesis >= hypotheses_ ||
        (verdict.alarm != 0 && verdict.alarm != 1)) {
      std::ostringstream message;
      message << "verdict hypothesis " << verdict.hypothesis << " (of " << hypotheses_
              << "), alarm " << verdict.alarm << " at t = " << evidence.t << " s";
      internal::ContractViolation(where_, message.str());
    }
    return Verdict{score_, verdict.hypothesis, verdict.alarm == 1, {}};
  }

 private:
  static void Copy(const Vec3& from, double* to) {
    for (int i = 0; i < 3; ++i) to[i] = from(i);
  }
  static void CopyMatrix(const Mat3& from, double* to) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) to[3 * r + c] = from(r, c);
    }
  }
  static void Convert(const HypothesisEvidence& from, moorsim_hypothesis_evidence& to) {
    Copy(from.innovation, to.innovation);
    CopyMatrix(from.covariance, to.covariance);
    to.log_likelihood = from.log_likelihood;
    to.dimension = from.dimension;
  }

  std::shared_ptr<const PluginLibrary> library_;
  const moorsim_detector_plugin* type_;
  void* instance_;
  std::string where_;  // "plugin <path> detector '<type>'", for the messages
  int hypotheses_ = 0;
  std::vector<std::array<int, 2>> failed_;  // per hypothesis, from SetPluginHypotheses
  std::vector<moorsim_hypothesis_evidence> hypothesis_;
  std::vector<double> line_load_;
  std::vector<double> score_;
  char error_[kErrorSize] = {};
};

// The declared table in the registry's form; throws InputError on a malformed one.
std::vector<DetectorParameter> Table(const std::string& path, const moorsim_detector_plugin& type) {
  const auto bad = [&](const std::string& what) {
    return InputError("plugin " + path + ": detector '" + std::string(Text(type.type)) +
                      "': " + what);
  };
  if (type.parameter_count < 0 || (type.parameter_count > 0 && type.parameters == nullptr)) {
    throw bad("parameter table missing");
  }
  std::vector<DetectorParameter> table;
  for (int i = 0; i < type.parameter_count; ++i) {
    const moorsim_parameter& p = type.parameters[i];
    if (Text(p.name).empty()) throw bad("parameter " + std::to_string(i) + " has no name");
    DetectorParameter entry;
    entry.name = p.name;
    if (p.has_default) entry.default_value = p.default_value;
    entry.range = ParameterRange{p.min, p.max, p.min_open != 0, p.max_open != 0, p.integer != 0};
    entry.unit = Text(p.unit);
    entry.description = Text(p.description);
    if (!(p.min <= p.max)) {  // also NaN
      throw bad("parameter '" + std::string(entry.name) + "' has the range [" +
                std::to_string(p.min) + ", " + std::to_string(p.max) + "]");
    }
    if (entry.default_value && !entry.range.Contains(*entry.default_value)) {
      throw bad("parameter '" + std::string(entry.name) + "' has a default outside its range");
    }
    if (!table.empty() && !(table.back().name < entry.name)) {
      throw bad("parameter table not sorted by name (or a name twice) at '" +
                std::string(entry.name) + "'");
    }
    table.push_back(entry);
  }
  return table;
}

// The libraries of --plugin, in order.
struct Registered {
  std::mutex mutex;
  std::vector<std::shared_ptr<const PluginLibrary>> libraries;
};
Registered& Registry() {
  static Registered registered;
  return registered;
}

}  // namespace

std::shared_ptr<const PluginLibrary> PluginLibrary::Load(const std::string& path) {
  std::shared_ptr<PluginLibrary> library(new PluginLibrary(path));
  const auto fail = [&](const std::string& why) {
    return InputError("plugin " + path + ": " + why);
  };
  dlerror();
  library->handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library->handle_ == nullptr) throw fail("cannot load (" + Reason(dlerror(), "?") + ")");
  library->sha256_ = FileSha256(path).value_or("");
  const auto symbol = [&](const char* name) {
    void* address = dlsym(library->handle_, name);
    if (address == nullptr) {
      throw fail(std::string("no entry point ") + name +
                 " (see detectors/plugin/moorsim_detector_plugin.h)");
    }
    return address;
  };
  // ISO C++ has no cast from an object pointer to a function pointer; POSIX guarantees the
  // conversion of what dlsym() returns.
  moorsim_plugin_abi_version_fn abi_version;
  void* abi_symbol = symbol("moorsim_plugin_abi_version");
  static_assert(sizeof(abi_version) == sizeof(abi_symbol));
  std::memcpy(&abi_version, &abi_symbol, sizeof(abi_version));
  const int version = abi_version();
  if (version != MOORSIM_DETECTOR_ABI_VERSION) {
    throw fail("built for detector plugin ABI version " + std::to_string(version) +
               ", this moorsim loads version " + std::to_string(MOORSIM_DETECTOR_ABI_VERSION) +
               " (rebuild the plugin against this moorsim's header)");
  }
  moorsim_detector_plugins_fn plugins;
  void* plugins_symbol = symbol("moorsim_detector_plugins");
  std::memcpy(&plugins, &plugins_symbol, sizeof(plugins));
  int count = 0;
  const moorsim_detector_plugin* types = plugins(&count);
  if (types == nullptr || count <= 0) throw fail("provides no detector types");
  library->types_ = std::span(types, static_cast<std::size_t>(count));
  for (const moorsim_detector_plugin& type : library->types_) {
    if (Text(type.type).empty()) throw fail("a detector type without a name");
    if (type.create == nullptr || type.reset == nullptr || type.step == nullptr ||
        type.destroy == nullptr) {
      throw fail("detector '" + std::string(type.type) + "' lacks a function");
    }
    if (library->Find(type.type) != &type) {
      throw fail("detector type '" + std::string(type.type) + "' given twice");
    }
    library->parameters_.push_back(Table(path, type));
  }
  return library;
}

PluginLibrary::~PluginLibrary() {
  if (handle_ != nullptr) dlclose(handle_);
}

std::vector<std::string_view> PluginLibrary::TypeNames() const {
  std::vector<std::string_view> names;
  for (const moorsim_detector_plugin& type : types_) names.push_back(type.type);
  return names;
}

const moorsim_detector_plugin* PluginLibrary::Find(std::string_view type) const {
  for (const moorsim_detector_plugin& entry : types_) {
    if (Text(entry.type) == type) return &entry;
  }
  return nullptr;
}

std::span<const DetectorParameter> PluginLibrary::Parameters(std::string_view type) const {
  const moorsim_detector_plugin* entry = Find(type);
  internal::Require(entry != nullptr, "PluginLibrary::Parameters", "a type of the library");
  return parameters_[static_cast<std::size_t>(entry - types_.data())];
}

std::unique_ptr<Detector> MakePluginDetector(const std::string& path, const DetectorSpec& spec,
                                             std::string_view key_path) {
  const std::string where(key_path);
  std::shared_ptr<const PluginLibrary> library;
  try {
    library = PluginLibrary::Load(path);
  } catch (const InputError& error) {
    throw InputError(where + ".plugin: " + error.what());
  }
  const moorsim_detector_plugin* type = library->Find(spec.type);
  if (type == nullptr) {
    throw InputError(where + ".type: plugin " + path + " has no detector '" + spec.type +
                     "' (it has: " + internal::JoinNames(library->TypeNames()) + ")");
  }
  const std::span<const DetectorParameter> table = library->Parameters(spec.type);
  internal::CheckParameters(spec, table, spec.type, key_path);
  std::vector<double> values;
  const DetectorParameters given(table, spec.parameters);
  for (const DetectorParameter& parameter : table) {
    values.push_back(given.Find(parameter.name).value_or(0.0));
  }
  char error[kErrorSize] = {};
  void* instance = type->create(values.data(), error, kErrorSize);
  if (instance == nullptr) {
    throw InputError(where + ": plugin " + path + " detector '" + spec.type +
                     "' refused its parameters: " + Reason(error, "no reason given"));
  }
  return std::make_unique<PluginDetector>(std::move(library), type, instance);
}

std::vector<std::shared_ptr<const PluginLibrary>> RegisteredPluginLibraries() {
  Registered& r = Registry();
  const std::lock_guard lock(r.mutex);
  return r.libraries;
}

std::shared_ptr<const PluginLibrary> RegisteredPluginFor(std::string_view type) {
  for (const std::shared_ptr<const PluginLibrary>& library : RegisteredPluginLibraries()) {
    if (library->Find(type) != nullptr) return library;
  }
  return nullptr;
}

void RegisterPluginLibrary(const std::string& path) {
  std::shared_ptr<const PluginLibrary> library = PluginLibrary::Load(path);
  Registered& r = Registry();
  const std::lock_guard lock(r.mutex);
  for (const std::shared_ptr<const PluginLibrary>& other : r.libraries) {
    if (other->path() == path) return;
  }
  const std::vector<std::string_view> built_in = DetectorTypes();
  for (std::string_view type : library->TypeNames()) {
    if (std::find(built_in.begin(), built_in.end(), type) != built_in.end()) {
      throw InputError("plugin " + path + ": detector '" + std::string(type) +
                       "' is a built-in detector's name (rename it, or name the library in "
                       "the scenario's `plugin:` key instead)");
    }
    for (const std::shared_ptr<const PluginLibrary>& other : r.libraries) {
      if (other->Find(type) != nullptr) {
        throw InputError("plugin " + path + ": detector '" + std::string(type) +
                         "' is provided by plugin " + other->path() + " too");
      }
    }
  }
  r.libraries.push_back(std::move(library));
}

std::shared_ptr<const PluginLibrary> PluginLibraryOf(const Detector& detector) {
  const auto* plugin = dynamic_cast<const PluginDetector*>(&detector);
  return plugin != nullptr ? plugin->library() : nullptr;
}

void SetPluginHypotheses(Detector& detector, std::vector<std::array<int, 2>> failed_lines) {
  if (auto* plugin = dynamic_cast<PluginDetector*>(&detector)) {
    plugin->SetFailedLines(std::move(failed_lines));
  }
}

}  // namespace moorsim::detectors
