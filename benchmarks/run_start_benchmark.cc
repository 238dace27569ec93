// What a run costs before its first step (a campaign pays it once per run): reading the
// WAMIT data, and building the whole coupled simulation (scenario parts, WAMIT data, the
// moored static start, the detectors' set-up) for the thesis case with its three detectors.
#include <benchmark/benchmark.h>

#include <memory>

#include "runner/scenario_plant.h"
#include "scenarios/load.h"
#include "simulation/simulation.h"
#include "vessel/hydro_data.h"

namespace {

const char* const kThesis = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_no_failure_current.yaml";

void BM_ReadWamit(benchmark::State& state) {
  const moorsim::scenarios::Scenario s = moorsim::scenarios::LoadScenario(kThesis);
  for (auto _ : state) {
    benchmark::DoNotOptimize(moorsim::vessel::ReadWamit(s.vessel->hydrodynamics));
  }
}
BENCHMARK(BM_ReadWamit)->Unit(benchmark::kMillisecond);

void BM_LoadScenario(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(moorsim::scenarios::LoadScenario(kThesis));
}
BENCHMARK(BM_LoadScenario)->Unit(benchmark::kMillisecond);

void BM_SimulationStart(benchmark::State& state) {
  const moorsim::scenarios::Scenario s = moorsim::scenarios::LoadScenario(kThesis);
  for (auto _ : state) {
    const std::unique_ptr<moorsim::simulation::Simulation> sim =
        moorsim::runner::MakeSimulation(s, 1);
    benchmark::DoNotOptimize(sim->time());
  }
}
BENCHMARK(BM_SimulationStart)->Unit(benchmark::kMillisecond);

}  // namespace
