// The cost of the library's interfaces over the work they call: the seed mooring
// (scenarios/library/seed_tapm.yaml, 8 lines x 50 segments) stepped every 0.1 s along a
// surge-heave harmonic, through CoupledLines::Step (the C++ call) and through
// moorsim_lines_step (the C API, with its checks and its exception barrier); and the
// whole state saved to bytes and restored. One iteration is one coupling step of 0.1 s;
// for the coupled plant (BM_CApiPlantSecond), one second of a 1 Hz control loop.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "mooring_fem/coupled_lines.h"
#include "moorsim/moorsim.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace {

constexpr const char* kSeed = MOORSIM_SOURCE_DIR "/scenarios/library/seed_tapm.yaml";
constexpr double kStep = 0.1;  // [s]

// Surge 5 m at 60 s and heave 1 m at 10 s: the body's pose and rate at t.
void Motion(double t, double* x, double* xd) {
  const double ws = 2 * std::numbers::pi / 60.0, wh = 2 * std::numbers::pi / 10.0;
  for (int d = 0; d < 6; ++d) x[d] = xd[d] = 0.0;
  x[0] = 5.0 * std::sin(ws * t);
  xd[0] = 5.0 * ws * std::cos(ws * t);
  x[2] = std::sin(wh * t);
  xd[2] = wh * std::cos(wh * t);
}

void BM_CoupledLinesStep(benchmark::State& state) {
  const auto scenario = moorsim::scenarios::LoadScenario(kSeed);
  moorsim::mooring_fem::CoupledLines lines(
      moorsim::scenarios::ToMooringParameters(scenario.mooring), scenario.solver);
  moorsim::mooring_fem::BodyDofs x{}, xd{};
  Motion(0.0, x.data(), xd.data());
  lines.Init(x, xd);
  double t = 0.0;
  for (auto _ : state) {
    t += kStep;
    Motion(t, x.data(), xd.data());
    benchmark::DoNotOptimize(lines.Step(x, xd, kStep));
  }
  state.counters["simulated_s_per_wall_s"] = benchmark::Counter(
      kStep * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_CApiStep(benchmark::State& state) {
  moorsim_lines* lines = moorsim_lines_create(kSeed);
  double x[6], xd[6], f[6], t = 0.0;
  Motion(0.0, x, xd);
  if (!lines || moorsim_lines_init(lines, x, xd) != MOORSIM_OK) {
    state.SkipWithError(moorsim_last_error());
    return;
  }
  for (auto _ : state) {
    double dt = kStep;
    Motion(t + kStep, x, xd);
    if (moorsim_lines_step(lines, x, xd, f, &t, &dt) != MOORSIM_OK) {
      state.SkipWithError(moorsim_last_error());
      break;
    }
    benchmark::DoNotOptimize(f);
  }
  state.counters["simulated_s_per_wall_s"] = benchmark::Counter(
      kStep * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  moorsim_lines_destroy(lines);
}

// The seed mooring after 10 s of motion, for the save and restore benchmarks.
moorsim_lines* MovedSeed() {
  moorsim_lines* lines = moorsim_lines_create(kSeed);
  double x[6], xd[6], f[6], t = 0.0;
  Motion(0.0, x, xd);
  moorsim_lines_init(lines, x, xd);
  for (int k = 1; k <= 100; ++k) {
    double dt = kStep;
    Motion(k * kStep, x, xd);
    moorsim_lines_step(lines, x, xd, f, &t, &dt);
  }
  return lines;
}

void BM_CApiSave(benchmark::State& state) {
  moorsim_lines* lines = MovedSeed();
  std::size_t size = 0;
  moorsim_lines_save(lines, nullptr, 0, &size);
  std::vector<unsigned char> buffer(size);
  for (auto _ : state) {
    moorsim_lines_save(lines, buffer.data(), buffer.size(), &size);
    benchmark::DoNotOptimize(buffer.data());
  }
  state.counters["bytes"] = static_cast<double>(size);
  moorsim_lines_destroy(lines);
}

void BM_CApiRestore(benchmark::State& state) {
  moorsim_lines* lines = MovedSeed();
  std::size_t size = 0;
  moorsim_lines_save(lines, nullptr, 0, &size);
  std::vector<unsigned char> buffer(size);
  moorsim_lines_save(lines, buffer.data(), buffer.size(), &size);
  for (auto _ : state) {
    if (moorsim_lines_restore(lines, buffer.data(), buffer.size()) != MOORSIM_OK) {
      state.SkipWithError(moorsim_last_error());
      break;
    }
  }
  state.counters["bytes"] = static_cast<double>(size);
  moorsim_lines_destroy(lines);
}

// The seed case's coupled plant with its controller, one second per iteration (a 1 Hz
// control loop's step) with the pose and the tensions read, as a caller's loop would.
void BM_CApiPlantSecond(benchmark::State& state) {
  moorsim_plant* plant = moorsim_plant_create(kSeed, 1);
  if (!plant) {
    state.SkipWithError(moorsim_last_error());
    return;
  }
  double t = 0.0, pose[6], tensions[8];
  for (auto _ : state) {
    t += 1.0;
    if (moorsim_plant_advance_to(plant, t) != MOORSIM_OK ||
        moorsim_plant_pose(plant, pose) != MOORSIM_OK ||
        moorsim_plant_fairlead_tensions(plant, tensions, 8) != MOORSIM_OK) {
      state.SkipWithError(moorsim_last_error());
      break;
    }
    benchmark::DoNotOptimize(pose);
  }
  moorsim_plant_destroy(plant);
}

}  // namespace

BENCHMARK(BM_CApiPlantSecond)->Unit(benchmark::kMicrosecond)->Iterations(600);
BENCHMARK(BM_CoupledLinesStep)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CApiStep)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CApiSave)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CApiRestore)->Unit(benchmark::kMicrosecond);
