// What one sample costs `moorsim detect` (live mode's latency target: under 1 ms per sample
// for the default bank): the thesis line-6 case's detection (EKF observer bank of 9
// hypotheses; DHT, MLE, GLR and the force-deficit test) taking the samples a 1000 s run of
// that case recorded, the line parting at 400 s. Each iteration is one sample; at the end
// of the record the detection starts over (outside the timing).
#include <benchmark/benchmark.h>

#include "runner/scenario_plant.h"
#include "scenarios/load.h"
#include "simulation/simulation.h"

namespace {

using moorsim::detectors::Observation;

const char* const kLine6 = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6.yaml";

// The samples the run's detection took, in order.
std::vector<Observation> RecordedSamples(const moorsim::scenarios::Scenario& s) {
  const std::unique_ptr<moorsim::simulation::Simulation> owned =
      moorsim::runner::MakeSimulation(s, s.simulation.seed);
  moorsim::simulation::Simulation& sim = *owned;
  sim.KeepDetectionInput(true);
  std::vector<Observation> samples;
  for (int t = 1; t <= 1000; ++t) {
    sim.AdvanceTo(t);
    const std::vector<Observation> taken = sim.Record().detection_input;
    samples.insert(samples.end(), taken.begin(), taken.end());
  }
  return samples;
}

// Argument 1: with every pair of lines too (37 hypotheses, detection.pairs).
void BM_DetectSample(benchmark::State& state) {
  const moorsim::scenarios::Scenario s = moorsim::scenarios::LoadScenario(
      kLine6, state.range(0) == 1 ? std::vector<std::string>{"detection.pairs=true"}
                                  : std::vector<std::string>{});
  const std::vector<Observation> samples = RecordedSamples(s);
  std::unique_ptr<moorsim::simulation::Detection> detection = moorsim::runner::MakeDetection(s);
  std::size_t next = 0;
  for (auto _ : state) {
    if (next == samples.size()) {
      state.PauseTiming();
      detection = moorsim::runner::MakeDetection(s);
      next = 0;
      state.ResumeTiming();
    }
    detection->Update(samples[next++]);
  }
  state.counters["samples"] = static_cast<double>(samples.size());
}
BENCHMARK(BM_DetectSample)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
