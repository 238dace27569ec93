// Micro benchmarks of detection: the cost per observation of the observer banks
// and of each detector, with the 9 hypotheses of the thesis mooring (intact + 8 lines; the
// pairs bank, 37 hypotheses, for the EKF bank too).
//
// Data: the thesis line-6 case's mooring (scenarios/library/thesis_line6_current.yaml,
// reference pose = its setpoint, heading -135 deg), the seed FPSO's low-frequency model, and
// 2000 observations at 1 Hz of a vessel at that pose with the thesis's sensor noise
// (variance 0.005 per DOF) and a slow 2 m, 300 s surge oscillation, generated once. The
// detectors run on the evidence the mixing EKF bank made of that data, also generated once,
// so their loops time the detector alone. Each benchmark cycles through the 2000 samples
// and restarts its observer or detector when it wraps (one restart per 2000 iterations).
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/random.h"
#include "detectors/deficit.h"
#include "detectors/dht.h"
#include "detectors/ekf_observer.h"
#include "detectors/glr.h"
#include "detectors/hypothesis_bank.h"
#include "detectors/mle.h"
#include "detectors/passive_observer.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace {

using namespace moorsim;
using namespace moorsim::detectors;

constexpr int kSamples = 2000;

const scenarios::Scenario& Thesis() {
  static const scenarios::Scenario scenario =
      scenarios::LoadScenario(MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6_current.yaml");
  return scenario;
}

Vec3 ReferencePose() { return Vec3(0.0, 0.0, -0.75 * std::numbers::pi); }

const HypothesisBank& Bank(bool pairs) {
  auto make = [](bool with_pairs) {
    HypothesisBankOptions options;
    options.include_pairs = with_pairs;
    options.reference_pose = ReferencePose();
    return HypothesisBank(scenarios::ToMooringParameters(Thesis().mooring), options);
  };
  static const HypothesisBank single = make(false);
  static const HypothesisBank with_pairs = make(true);
  return pairs ? with_pairs : single;
}

const std::vector<Observation>& Observations() {
  static const std::vector<Observation> data = [] {
    RandomStream x = RandomStream::Derive(1, "bench.x");
    RandomStream y = RandomStream::Derive(1, "bench.y");
    RandomStream psi = RandomStream::Derive(1, "bench.psi");
    const double sigma = std::sqrt(0.005);
    std::vector<Observation> out(kSamples);
    for (int k = 0; k < kSamples; ++k) {
      const double surge = 2.0 * std::sin(2.0 * std::numbers::pi * k / 300.0);
      out[k].t = k;
      out[k].pose = ReferencePose() +
                    Vec3(surge + sigma * x.Normal(), sigma * y.Normal(), sigma * psi.Normal());
    }
    return out;
  }();
  return data;
}

const std::vector<Evidence>& EvidenceStream() {
  static const std::vector<Evidence> data = [] {
    ObserverBank bank(Bank(false), SeedLowFrequencyModel());
    std::vector<Evidence> out;
    out.reserve(kSamples);
    for (const Observation& o : Observations()) out.push_back(bank.Update(o));
    return out;
  }();
  return data;
}

template <class Observers>
void RunObservers(benchmark::State& state, Observers& observers) {
  const std::vector<Observation>& data = Observations();
  int k = 0;
  for (auto _ : state) {
    if (k == kSamples) {
      observers.Reset();
      k = 0;
    }
    benchmark::DoNotOptimize(observers.Update(data[k++]));
  }
  state.counters["hypotheses"] = observers.size();
}

void BM_EkfBank(benchmark::State& state) {
  const bool pairs = state.range(0) != 0;
  const double switch_rate = state.range(1) != 0 ? ObserverBankOptions{}.switch_rate : 0.0;
  ObserverBank observers(Bank(pairs), SeedLowFrequencyModel(), EkfOptions{},
                         ObserverBankOptions{.switch_rate = switch_rate, .sensor_checks = {}});
  RunObservers(state, observers);
}
// {pairs, mixing}
BENCHMARK(BM_EkfBank)->Args({0, 1})->Args({0, 0})->Args({1, 1})->Unit(benchmark::kMicrosecond);

void BM_PassiveBank(benchmark::State& state) {
  const HypothesisBank& bank = Bank(false);
  // Covariances of the order the training gives; the cost does not depend on them.
  const std::vector<Mat3> covariances(bank.size(), Vec3(0.03, 0.03, 0.01).asDiagonal());
  PassiveObserverBank observers(bank, SeedLowFrequencyModel(), PassiveObserverOptions{},
                                covariances);
  RunObservers(state, observers);
}
BENCHMARK(BM_PassiveBank)->Unit(benchmark::kMicrosecond);

template <class D>
void RunDetector(benchmark::State& state, D& detector) {
  const std::vector<Evidence>& data = EvidenceStream();
  const int hypotheses = static_cast<int>(data.front().hypotheses.size());
  detector.Reset(hypotheses);
  int k = 0;
  for (auto _ : state) {
    if (k == kSamples) {
      detector.Reset(hypotheses);
      k = 0;
    }
    benchmark::DoNotOptimize(detector.Step(data[k++]));
  }
}

void BM_Dht(benchmark::State& state) {
  Dht dht;
  RunDetector(state, dht);
}
BENCHMARK(BM_Dht)->Unit(benchmark::kNanosecond);

void BM_Mle(benchmark::State& state) {
  Mle mle;
  RunDetector(state, mle);
}
BENCHMARK(BM_Mle)->Unit(benchmark::kNanosecond);

void BM_Glr(benchmark::State& state) {
  Glr glr(GlrOptions{.threshold = 120.0, .hold = 15.0});
  glr.SetSignatures(std::vector<Vec3>(8, Vec3(1.0, 0.5, 0.0)));
  RunDetector(state, glr);
}
BENCHMARK(BM_Glr)->Unit(benchmark::kNanosecond);

// The evidence carries the bank's load evidence (bias, wave motion, failed-line loads), so
// the force-deficit test runs on it as in a simulation.
void BM_Deficit(benchmark::State& state) {
  Deficit deficit;
  RunDetector(state, deficit);
}
BENCHMARK(BM_Deficit)->Unit(benchmark::kNanosecond);

}  // namespace
