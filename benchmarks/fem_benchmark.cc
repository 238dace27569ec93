// Micro benchmarks of the lumped-mass FEM (mooring_fem/mooring_system.h): right-hand side,
// analytic Jacobian, the Newton matrix's factorisation and solve (the block solver of
// core/block_solver.h against KLU), static settling and the analytic catenary, on the seed mooring
// (scenarios/library/seed_tapm.yaml) with every line's segment count overridden.
//
// Arguments: {lines, segments}. `lines` keeps the first 1 or 8 lines of the seed case.
// The RHS and Jacobian are evaluated at the FEM's static equilibrium for fairleads at the
// vessel origin, plus small random node velocities so the drag, structural damping and
// seabed friction paths are all active. All setup (loading, settling) is outside the timed
// loop and cached per argument pair, since Google Benchmark calls each function repeatedly.
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "core/block_solver.h"
#include "core/ode_system.h"
#include "core/types.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/parameters.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "scenarios/scenario.h"

namespace {

using moorsim::PointKinematics;
using moorsim::Vec3;
using moorsim::mooring_fem::MooringSystem;

const moorsim::scenarios::Scenario& SeedScenario() {
  static const moorsim::scenarios::Scenario scenario =
      moorsim::scenarios::LoadScenario(MOORSIM_SOURCE_DIR "/scenarios/library/seed_tapm.yaml");
  return scenario;
}

/// The seed mooring with its first `lines` lines, each split into `segments` segments.
/// `composite`: each line instead 400 m of the seed chain, 1650 m of polyester rope and
/// 200 m of chain (2250 m, as the seed line) with a 20 t clump weight on the lower joint,
/// its `segments` shared 20 / 70 / 10 % between the three: the same state size.
moorsim::mooring_fem::MooringParameters SeedSpec(int lines, int segments, bool composite = false) {
  moorsim::mooring_fem::MooringParameters spec =
      moorsim::scenarios::ToMooringParameters(SeedScenario().mooring);
  if (static_cast<int>(spec.lines.size()) > lines) spec.lines.resize(lines);
  if (composite) {
    spec.line_types.push_back(moorsim::mooring_fem::PolyesterRope());
  }
  for (auto& line : spec.lines) {
    if (!composite) {
      line.sections.front().segments = segments;
      continue;
    }
    const std::string chain = line.sections.front().type;
    const int bottom = std::max(1, segments / 5);
    const int top = std::max(1, segments / 10);
    line.sections = {{chain, 400.0, bottom},
                     {"polyester", 1650.0, segments - bottom - top},
                     {chain, 200.0, top}};
    line.joints = {{20000.0, 2.55, 1.0, 2.0}, {}};
  }
  return spec;
}

/// Earth-frame fairlead positions for the vessel at the origin.
std::vector<Vec3> FairleadPositions(const MooringSystem& mooring) {
  std::vector<Vec3> positions;
  for (int i = 0; i < mooring.num_lines(); ++i) {
    positions.push_back(moorsim::mooring_fem::FairleadPosition(moorsim::mooring_fem::PlanarPose{},
                                                               mooring.line(i).fairlead_body));
  }
  return positions;
}

/// A settled mooring with small random node velocities.
struct Fixture {
  Fixture(int lines, int segments, bool composite = false)
      : mooring(SeedSpec(lines, segments, composite)) {
    positions = FairleadPositions(mooring);
    fairleads.resize(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) fairleads[i].position = positions[i];
    x.resize(mooring.StateSize());
    mooring.CatenaryState(positions, x.data());
    mooring.SettleStatic(positions, x.data());
    // Small node velocities: well above the friction regularisation speed (0.01 m/s), so
    // grounded nodes slide, and small enough to stay a plausible state.
    std::mt19937 rng(12345);
    std::normal_distribution<double> dist(0.0, 0.05);
    const std::vector<char> kinds = mooring.StateKinds();
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (kinds[i] == 'v') x[i] = dist(rng);
    }
    xdot.resize(x.size());
    jacobian.resize(static_cast<std::size_t>(mooring.JacobianPattern().nnz()));
  }

  int num_nodes() const { return mooring.StateSize() / 6; }

  MooringSystem mooring;
  std::vector<Vec3> positions;
  std::vector<PointKinematics> fairleads;
  std::vector<double> x;
  std::vector<double> xdot;
  std::vector<double> jacobian;
};

Fixture& GetFixture(int lines, int segments, bool composite = false) {
  static std::map<std::tuple<int, int, bool>, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[{lines, segments, composite}];
  if (!slot) slot = std::make_unique<Fixture>(lines, segments, composite);
  return *slot;
}

void BM_Rhs(benchmark::State& state, bool composite) {
  Fixture& f =
      GetFixture(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), composite);
  const std::span<const PointKinematics> fairleads(f.fairleads);
  for (auto _ : state) {
    f.mooring.Derivatives(f.x.data(), fairleads, f.xdot.data());
    benchmark::DoNotOptimize(f.xdot.data());
    benchmark::ClobberMemory();
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["state"] = f.mooring.StateSize();
  state.counters["nodes/s"] =
      benchmark::Counter(iterations * f.num_nodes(), benchmark::Counter::kIsRate);
  state.counters["rhs/s"] = benchmark::Counter(iterations, benchmark::Counter::kIsRate);
}

void BM_Jacobian(benchmark::State& state, bool composite) {
  Fixture& f =
      GetFixture(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), composite);
  const std::span<const PointKinematics> fairleads(f.fairleads);
  for (auto _ : state) {
    f.mooring.Jacobian(f.x.data(), fairleads, f.jacobian.data());
    benchmark::DoNotOptimize(f.jacobian.data());
    benchmark::ClobberMemory();
  }
  state.counters["state"] = f.mooring.StateSize();
  state.counters["nnz"] = static_cast<double>(f.mooring.JacobianPattern().nnz());
  state.counters["jac/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// gamma = h beta of a 0.1 s BDF2 step.
constexpr double kNewtonGamma = 0.1 * 2.0 / 3.0;

// The Newton matrix M = I - gamma J of the lines, as CVODE forms it for KLU (the block
// solver takes J and gamma; f.jacobian holds J after this).
std::vector<double> NewtonMatrix(Fixture& f) {
  const std::span<const PointKinematics> fairleads(f.fairleads);
  f.mooring.Jacobian(f.x.data(), fairleads, f.jacobian.data());
  const moorsim::SparsityPattern& p = f.mooring.JacobianPattern();
  std::vector<double> m(f.jacobian.size());
  for (int r = 0; r < p.size; ++r) {
    for (int64_t j = p.row_start[r]; j < p.row_start[r + 1]; ++j) {
      m[j] = (p.column[j] == r ? 1.0 : 0.0) - kNewtonGamma * f.jacobian[j];
    }
  }
  return m;
}

// KLU through SUNDIALS, set up as the integrator does (no scaling), on the same matrix.
struct KluSolver {
  explicit KluSolver(const moorsim::SparsityPattern& p, const std::vector<double>& values) {
    SUNContext_Create(nullptr, &ctx);
    const int n = p.size;
    A = SUNSparseMatrix(n, n, p.nnz(), CSR_MAT, ctx);
    std::copy(p.row_start.begin(), p.row_start.end(), SUNSparseMatrix_IndexPointers(A));
    std::copy(p.column.begin(), p.column.end(), SUNSparseMatrix_IndexValues(A));
    std::copy(values.begin(), values.end(), SUNSparseMatrix_Data(A));
    x = N_VNew_Serial(n, ctx);
    b = N_VNew_Serial(n, ctx);
    LS = SUNLinSol_KLU(x, A, ctx);
    SUNLinSol_KLUGetCommon(LS)->scale = -1;
    SUNLinSolInitialize(LS);
    SUNLinSolSetup(LS, A);  // the symbolic analysis, once per topology
  }
  ~KluSolver() {
    SUNLinSolFree(LS);
    N_VDestroy(x);
    N_VDestroy(b);
    SUNMatDestroy(A);
    SUNContext_Free(&ctx);
  }
  SUNContext ctx = nullptr;
  SUNMatrix A = nullptr;
  N_Vector x = nullptr, b = nullptr;
  SUNLinearSolver LS = nullptr;
};

// state.range(2): 0 = KLU, 1 = the block solver.
void BM_NewtonFactor(benchmark::State& state) {
  Fixture& f = GetFixture(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const std::vector<double> m = NewtonMatrix(f);
  const moorsim::SparsityPattern& p = f.mooring.JacobianPattern();
  if (state.range(2) == 0) {
    KluSolver klu(p, m);
    for (auto _ : state) benchmark::DoNotOptimize(SUNLinSolSetup(klu.LS, klu.A));
  } else {
    moorsim::BorderedBlockSolver block(p, f.mooring.Blocks());
    for (auto _ : state) benchmark::DoNotOptimize(block.Factor(f.jacobian.data(), kNewtonGamma));
  }
  state.SetLabel(state.range(2) == 0 ? "klu" : "block");
  state.counters["state"] = f.mooring.StateSize();
}

void BM_NewtonSolve(benchmark::State& state) {
  Fixture& f = GetFixture(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const std::vector<double> m = NewtonMatrix(f);
  const moorsim::SparsityPattern& p = f.mooring.JacobianPattern();
  std::vector<double> rhs(p.size), out(p.size);
  for (int i = 0; i < p.size; ++i) rhs[i] = std::sin(0.37 * i);
  if (state.range(2) == 0) {
    KluSolver klu(p, m);
    SUNLinSolSetup(klu.LS, klu.A);
    for (auto _ : state) {
      std::copy(rhs.begin(), rhs.end(), N_VGetArrayPointer(klu.b));
      benchmark::DoNotOptimize(SUNLinSolSolve(klu.LS, klu.A, klu.x, klu.b, 0.0));
    }
  } else {
    moorsim::BorderedBlockSolver block(p, f.mooring.Blocks());
    block.Factor(f.jacobian.data(), kNewtonGamma);
    for (auto _ : state) {
      block.Solve(rhs.data(), out.data());
      benchmark::DoNotOptimize(out.data());
      benchmark::ClobberMemory();
    }
  }
  state.SetLabel(state.range(2) == 0 ? "klu" : "block");
  state.counters["state"] = f.mooring.StateSize();
}

// The cost of `moorsim static`: analytic catenary placement, then Newton on the FEM.
void BM_StaticSettle(benchmark::State& state) {
  MooringSystem mooring(
      SeedSpec(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))));
  const std::vector<Vec3> positions = FairleadPositions(mooring);
  std::vector<double> x(mooring.StateSize());
  double residual = 0.0;
  for (auto _ : state) {
    mooring.CatenaryState(positions, x.data());
    residual = mooring.SettleStatic(positions, x.data());
    benchmark::DoNotOptimize(residual);
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  state.counters["state"] = mooring.StateSize();
  state.counters["residual_N"] = residual;
  state.counters["settle/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// One seed line (line 1), fairlead at the vessel origin.
void BM_Catenary(benchmark::State& state) {
  const MooringSystem mooring(SeedSpec(1, 50));
  const moorsim::mooring_fem::LineProperties& lp = mooring.line(0);
  const moorsim::mooring_fem::SectionProperties& sp = lp.sections.front();
  const moorsim::mooring_fem::CatenaryLineProperties props{sp.length, sp.weight_per_length,
                                                           sp.axial_stiffness};
  const Vec3 anchor = lp.anchor;
  const Vec3 fairlead = FairleadPositions(mooring)[0];
  for (auto _ : state) {
    benchmark::DoNotOptimize(props);
    benchmark::DoNotOptimize(anchor);
    benchmark::DoNotOptimize(fairlead);
    moorsim::mooring_fem::LineCatenary cat =
        moorsim::mooring_fem::SolveLineCatenary(props, anchor, fairlead);
    benchmark::DoNotOptimize(cat);
    benchmark::ClobberMemory();
  }
  state.counters["solves/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_Rhs, , false)
    ->Name("BM_Rhs")
    ->ArgsProduct({{1, 8}, {20, 50, 100}})
    ->ArgNames({"lines", "segments"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Jacobian, , false)
    ->Name("BM_Jacobian")
    ->ArgsProduct({{1, 8}, {20, 50, 100}})
    ->ArgNames({"lines", "segments"})
    ->Unit(benchmark::kMicrosecond);
// Composite lines of the same segment count as the homogeneous ones (SeedSpec).
BENCHMARK_CAPTURE(BM_Rhs, , true)
    ->Name("BM_RhsComposite")
    ->Args({8, 50})
    ->ArgNames({"lines", "segments"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Jacobian, , true)
    ->Name("BM_JacobianComposite")
    ->Args({8, 50})
    ->ArgNames({"lines", "segments"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NewtonFactor)
    ->ArgsProduct({{8}, {50, 100}, {0, 1}})
    ->ArgNames({"lines", "segments", "block"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NewtonSolve)
    ->ArgsProduct({{8}, {50, 100}, {0, 1}})
    ->ArgNames({"lines", "segments", "block"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StaticSettle)
    ->ArgsProduct({{8}, {20, 50, 100}})
    ->ArgNames({"lines", "segments"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Catenary)->Unit(benchmark::kMicrosecond);

}  // namespace
