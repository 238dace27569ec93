#include "simulation/detection.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>

#include "core/error.h"
#include "detectors/ekf_observer.h"
#include "detectors/glr_signatures.h"
#include "detectors/hypothesis_bank.h"
#include "detectors/innovation_covariance.h"
#include "detectors/passive_observer.h"
#include "detectors/plugin_detector.h"
#include "detectors/registry.h"
#include "simulation/detection_models.h"
#include "simulation/shared_parts.h"

namespace moorsim::simulation {

namespace {

/// Builds detector i; an InputError from the registry says "detectors[<i+1>]...".
std::unique_ptr<detectors::Detector> BuildDetector(const DetectionSetup& setup, std::size_t i) {
  const std::string path = "detectors[" + std::to_string(i + 1) + "]";
  const detectors::DetectorSpec& spec = setup.detectors[i];
  std::unique_ptr<detectors::Detector> detector = detectors::MakeDetector(spec, path);
  if (detector->NeedsLoadEvidence() && setup.observer == ObserverType::kPassive) {
    throw InputError(path + ".type: " + spec.type +
                     " reads the EKF observers' load estimate, which "
                     "detection.observer: passive does not give (use ekf)");
  }
  return detector;
}

/// The part `build` makes, shared between plants of the same `key` within the process, or
/// built for this one alone when the key is empty (a model without an identity).
template <typename T, typename Build>
std::shared_ptr<const T> SharedOrOwn(const std::string& key, Build build) {
  if (key.empty()) return std::make_shared<const T>(build());
  return SharedPart<T>(key, build);
}

}  // namespace

void CheckDetectors(const DetectionSetup& setup) {
  for (std::size_t i = 0; i < setup.detectors.size(); ++i) BuildDetector(setup, i);
}

struct Detection::Parts {
  std::shared_ptr<const detectors::HypothesisBank> bank;  // shared between runs (read only)
  std::optional<detectors::ObserverBank> observers;       // detection.observer: ekf
  std::optional<detectors::PassiveObserverBank> passive;  // detection.observer: passive
  std::vector<std::unique_ptr<detectors::Detector>> detectors;
  std::vector<detectors::Verdict> verdicts;
  std::optional<Vec3> bias, wave_motion;  // the latest load picture
  std::optional<VecX> expected_tensions;  // the latest sample's, with cells
};

Detection::Detection(const PlantModel& plant, const vessel::VesselModel& vessel,
                     const Vec6& moored_pose)
    : parts_(std::make_unique<Parts>()) {
  const auto start = std::chrono::steady_clock::now();
  Parts& p = *parts_;
  const DetectionSetup& setup = plant.detection.value();
  const DetectionModels models = MakeDetectionModels(setup, vessel, moored_pose);
  const detectors::HypothesisBankOptions& options = models.bank;
  // The bank, the GLR signatures and the passive observers' training depend on the set-up
  // (not on the seed, the failure or the run's length) and on the calm-water moored pose,
  // which the set-up alone determines: every run of a set-up shares them (shared_parts.h).
  // The heave stays in the key so that the key names everything the parts are built from.
  std::string key;
  if (!setup.identity.empty()) {
    char heave[40];
    std::snprintf(heave, sizeof heave, "\nmoored heave %a", moored_pose(2));
    key = setup.identity + heave;
  }
  p.bank = SharedOrOwn<detectors::HypothesisBank>(
      key, [&] { return detectors::HypothesisBank(plant.mooring, options); });
  const detectors::LowFrequencyModel& model = models.model;
  const detectors::EkfOptions& ekf = models.ekf;
  const double sample_interval = 1.0 / plant.pose_sensors.gnss_rate;
  if (setup.observer == ObserverType::kPassive) {
    // The TAPM thesis's passive observers, each with the innovation covariance of a 10000 s
    // training run of its own hypothesis's model (section 4.4), held at the setpoint, with
    // the noise levels of detection.model; streams "training.*" of detection.training_seed.
    detectors::PassiveObserverOptions passive;
    passive.bias_time_constant = ekf.bias_time_constant;
    passive.mooring_damping_ratio = ekf.mooring_damping_ratio;
    // Trained once per set-up (detection.training_seed, not the run seed) and shared by
    // every run of it in the process, as a vessel's covariances are trained once.
    detectors::CovarianceTrainingOptions training;
    training.pose = options.reference_pose;
    training.sample_interval = sample_interval;
    training.seed = setup.training_seed;
    p.passive.emplace(
        *p.bank, model, passive,
        *SharedOrOwn<std::vector<Mat3>>(key.empty() ? key : key + "\npassive training", [&] {
          return detectors::TrainPassiveCovariances(*p.bank, model, passive, ekf, training);
        }));
  } else {
    p.observers.emplace(*p.bank, model, ekf, models.observer_bank);
  }
  // The failure signatures of the same models, per window, shared like the bank.
  class SharedSignatures final : public detectors::SignatureSource {
   public:
    explicit SharedSignatures(std::function<std::shared_ptr<const std::vector<Vec3>>(int)> make)
        : make_(std::move(make)) {}
    const std::vector<Vec3>& Signatures(int window) const override {
      std::shared_ptr<const std::vector<Vec3>>& held = held_[window];
      if (!held) held = make_(window);
      return *held;
    }

   private:
    std::function<std::shared_ptr<const std::vector<Vec3>>(int)> make_;
    mutable std::map<int, std::shared_ptr<const std::vector<Vec3>>> held_;
  };
  const SharedSignatures signatures([&](int window) {
    return SharedOrOwn<std::vector<Vec3>>(
        key.empty() ? key : key + "\nGLR window " + std::to_string(window), [&] {
          return detectors::GlrSignatures(*p.bank, model, ekf, options.reference_pose,
                                          sample_interval, window);
        });
  });
  const std::vector<std::array<int, 2>> failed = FailedLines();
  for (std::size_t i = 0; i < setup.detectors.size(); ++i) {
    p.detectors.push_back(BuildDetector(setup, i));
    detectors::Detector& detector = *p.detectors.back();
    detectors::SetPluginHypotheses(detector, failed);
    detector.Prepare(signatures);
    detector.Reset(p.bank->size());
    DetectorRecord record;
    record.label = setup.detectors[i].label;
    record.type = setup.detectors[i].type;
    if (plant.failure) record.failure_time = plant.failure->time;
    record.threshold = detector.AlarmThreshold();
    records_.push_back(record);
  }
  p.verdicts.assign(p.detectors.size(), detectors::Verdict{});
  for (detectors::Verdict& v : p.verdicts) v.score.assign(p.bank->size(), 0.0);
  timing_.setup_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Detection::~Detection() = default;

void Detection::Update(const detectors::Observation& observation) {
  const auto start = std::chrono::steady_clock::now();
  Parts& p = *parts_;
  if (keep_input_) input_.push_back(observation);
  const detectors::Evidence& evidence =
      p.observers ? p.observers->Update(observation) : p.passive->Update(observation);
  if (evidence.load) {
    p.bias = evidence.load->bias;
    p.wave_motion = evidence.load->wave_motion;
  }
  if (evidence.tensions) p.expected_tensions = evidence.tensions->expected;
  for (std::size_t i = 0; i < p.detectors.size(); ++i) {
    const detectors::Verdict& v = p.verdicts[i] = p.detectors[i]->Update(evidence);
    records_[i].history.Update(observation.t, v.alarm, v.hypothesis);
    records_[i].sensor_faults.Update(observation.t, v.faulty_sensors);
  }
  timing_.update_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++timing_.samples;
}

std::vector<detectors::Observation> Detection::TakeInput() {
  std::vector<detectors::Observation> taken;
  taken.swap(input_);
  return taken;
}

int Detection::num_hypotheses() const { return parts_->bank->size(); }

std::vector<std::string> Detection::HypothesisLabels() const {
  std::vector<std::string> labels;
  for (int h = 0; h < num_hypotheses(); ++h) labels.push_back(parts_->bank->Label(h));
  return labels;
}

std::vector<std::array<int, 2>> Detection::FailedLines() const {
  std::vector<std::array<int, 2>> failed(static_cast<std::size_t>(num_hypotheses()), {0, 0});
  for (int h = 0; h < num_hypotheses(); ++h) {
    const std::span<const int> lines = parts_->bank->failed_lines(h);
    for (std::size_t k = 0; k < lines.size() && k < 2; ++k) failed[h][k] = lines[k];
  }
  return failed;
}

bool Detection::estimates_load() const { return parts_->observers.has_value(); }

const std::vector<detectors::Verdict>& Detection::verdicts() const { return parts_->verdicts; }

const std::optional<Vec3>& Detection::bias() const { return parts_->bias; }

const std::optional<Vec3>& Detection::wave_motion() const { return parts_->wave_motion; }
const std::optional<VecX>& Detection::expected_tensions() const {
  return parts_->expected_tensions;
}

std::vector<std::shared_ptr<const detectors::PluginLibrary>> Detection::PluginLibraries() const {
  std::vector<std::shared_ptr<const detectors::PluginLibrary>> libraries;
  for (const std::unique_ptr<detectors::Detector>& d : parts_->detectors) {
    if (auto library = detectors::PluginLibraryOf(*d);
        library != nullptr &&
        std::find(libraries.begin(), libraries.end(), library) == libraries.end()) {
      libraries.push_back(std::move(library));
    }
  }
  return libraries;
}

nlohmann::json PluginsSummary(
    const std::vector<std::shared_ptr<const detectors::PluginLibrary>>& used) {
  std::vector<std::shared_ptr<const detectors::PluginLibrary>> libraries = used;
  for (auto& library : detectors::RegisteredPluginLibraries()) libraries.push_back(library);
  nlohmann::json plugins = nlohmann::json::array();
  std::vector<std::string> seen;
  for (const auto& library : libraries) {
    if (std::find(seen.begin(), seen.end(), library->path()) != seen.end()) continue;
    seen.push_back(library->path());
    plugins.push_back({{"path", library->path()}, {"sha256", library->sha256()}});
  }
  return plugins;
}

nlohmann::ordered_json AlarmEventJson(const DetectorRecord& record, const detectors::AlarmEvent& e,
                                      const detectors::Verdict& verdict,
                                      const std::vector<std::string>& labels, int lines,
                                      double latency_ms) {
  const bool end = e.kind == detectors::AlarmEvent::Kind::kEnd;
  nlohmann::ordered_json j;
  j["time"] = e.time;
  j["detector"] = record.label;
  j["type"] = record.type;
  j["event"] = detectors::AlarmEventName(e.kind);
  j["hypothesis"] = end ? nlohmann::json(nullptr) : nlohmann::json(labels.at(e.hypothesis));
  j["line"] = !end && e.hypothesis >= 1 && e.hypothesis <= lines ? nlohmann::json(e.hypothesis)
                                                                 : nlohmann::json(nullptr);
  j["score"] = end ? nlohmann::json(nullptr) : nlohmann::json(verdict.score.at(e.hypothesis));
  j["latency_ms"] = latency_ms;
  return j;
}

}  // namespace moorsim::simulation
