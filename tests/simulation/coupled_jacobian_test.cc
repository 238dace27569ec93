// The coupled system's analytic Jacobian (vessel + lines + coupling blocks) against central
// finite differences of its own right-hand side, over the whole state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "core/block_solver.h"
#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"
#include "tests/simulation/test_scenarios.h"

namespace moorsim::simulation {
namespace {

void CheckJacobian(Simulation& sim, std::vector<double> x, double t) {
  CoupledSystem& system = sim.system();
  const int n = system.StateSize();
  const SparsityPattern& pattern = system.JacobianPattern();
  std::vector<double> f(n), values(pattern.nnz());
  system.Derivatives(t, x.data(), f.data());
  system.Jacobian(t, x.data(), f.data(), values.data());
  // Dense analytic Jacobian from the pattern.
  Eigen::MatrixXd analytic = Eigen::MatrixXd::Zero(n, n);
  for (int r = 0; r < n; ++r) {
    for (int64_t j = pattern.row_start[r]; j < pattern.row_start[r + 1]; ++j) {
      analytic(r, pattern.column[j]) = values[j];
    }
  }
  std::vector<double> fp(n), fm(n);
  Eigen::MatrixXd numeric(n, n);
  for (int c = 0; c < n; ++c) {
    // Steps: ~1e-6 of each state's scale (positions ~1e3 m, angles ~1, thrust ~1e5 N).
    const double h = 1e-6 * std::max(1.0, std::abs(x[c])) * (c >= 12 && c < 15 ? 1e4 : 1.0);
    const double saved = x[c];
    x[c] = saved + h;
    system.Derivatives(t, x.data(), fp.data());
    x[c] = saved - h;
    system.Derivatives(t, x.data(), fm.data());
    x[c] = saved;
    for (int r = 0; r < n; ++r) numeric(r, c) = (fp[r] - fm[r]) / (2 * h);
  }
  // Compare row by row relative to the row's largest entry: central differences with these
  // steps carry ~1e-6 relative truncation and rounding error; the smooth seabed and friction
  // regularisations are resolved by them. A wrong or missing block is off by O(1).
  int failures = 0;
  for (int r = 0; r < n; ++r) {
    const double scale = std::max(numeric.row(r).cwiseAbs().maxCoeff(), 1e-12);
    for (int c = 0; c < n; ++c) {
      const double diff = std::abs(analytic(r, c) - numeric(r, c));
      if (diff > 1e-4 * scale + 1e-9) {
        if (++failures <= 10) {
          ADD_FAILURE() << "J(" << r << ", " << c << ") analytic " << analytic(r, c) << " numeric "
                        << numeric(r, c) << " (row scale " << scale << ")";
        }
      }
    }
  }
  EXPECT_EQ(failures, 0);
}

// The Newton matrices I - gamma J of the coupled system solved by the block solver (the
// vessel as the border, the lines' chains after it) against a dense LU, at CVODE's step
// sizes and far beyond them.
void CheckBlockSolve(Simulation& sim, const std::vector<double>& x, double t) {
  CoupledSystem& system = sim.system();
  const int n = system.StateSize();
  const SparsityPattern& pattern = system.JacobianPattern();
  ASSERT_NE(system.Blocks(), nullptr);
  BorderedBlockSolver solver(pattern, *system.Blocks());
  std::vector<double> f(n), jacobian(pattern.nnz());
  system.Derivatives(t, x.data(), f.data());
  system.Jacobian(t, x.data(), f.data(), jacobian.data());
  for (const double gamma : {0.01, 0.1, 1.0}) {
    Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(n, n);
    for (int r = 0; r < n; ++r) {
      for (int64_t j = pattern.row_start[r]; j < pattern.row_start[r + 1]; ++j) {
        dense(r, pattern.column[j]) -= gamma * jacobian[j];
      }
    }
    ASSERT_TRUE(solver.Factor(jacobian.data(), gamma)) << "gamma " << gamma;
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = std::sin(0.7 * i) * (i < 12 ? 1.0 : 1e-2);
    const Eigen::VectorXd reference = dense.partialPivLu().solve(b);
    Eigen::VectorXd solution(n);
    solver.Solve(b.data(), solution.data());
    EXPECT_LT((solution - reference).norm(), 1e-9 * reference.norm()) << "gamma " << gamma;
    EXPECT_LT((dense * solution - b).norm(), 1e-9 * b.norm()) << "gamma " << gamma;
  }
}

// A state away from rest in all six DOFs, with body velocities, thrust, node velocities and
// (with a turning turret) a turret angle and a relative rate `turret_rate`.
std::vector<double> AwayFromRest(Simulation& sim, double turret_rate = 0.0) {
  std::vector<double> x = sim.state();
  const double offset[6] = {3.0, -2.0, 0.2, 0.01, -0.008, 0.05};
  const double velocity[6] = {0.3, -0.2, 0.05, 0.004, -0.003, 0.002};
  for (int i = 0; i < 6; ++i) {
    x[i] += offset[i];
    x[6 + i] = velocity[i];
  }
  for (int k = 12; k < 15; ++k) x[k] = 2e5 * (k - 11);
  if (sim.plant().turret_turns()) {
    const int a = sim.plant().turret_state();
    x[a] = 0.1;
    x[a + 1] = velocity[5] + turret_rate;
  }
  const std::size_t nodes = static_cast<std::size_t>(sim.plant().StateSize());
  const std::vector<char> kinds = sim.mooring().StateKinds();
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    if (kinds[i] == 'v') x[nodes + i] = 0.05 * std::sin(0.37 * (nodes + i - i % 6) + i % 6);
  }
  return x;
}

TEST(CoupledJacobian, MatchesFiniteDifferencesAwayFromRest) {
  scenarios::Scenario scenario = testing::SeedVesselScenario();
  for (auto& line : scenario.mooring.lines)
    line.sections.front().segments = 10;  // a small system, same blocks
  Simulation sim(scenarios::ToPlantModel(scenario), 1);
  CheckJacobian(sim, AwayFromRest(sim), 10.0);
  CheckBlockSolve(sim, AwayFromRest(sim), 10.0);
}

TEST(CoupledJacobian, BlockSolverAfterLinesPart) {
  // Line 6 parted at its fairlead (an anchored chain with a free top: not coupled), line 2
  // at an internal node (an anchored lower piece and an upper piece hanging from the vessel
  // with a free lower end), line 3's anchor let go (a free lower end, coupled on top).
  const std::pair<const char*, std::size_t> cases[] = {
      {"failure: {line: 6, time: 0.5, mode: fairlead}", 8},
      {"failure: {line: 2, time: 0.5, mode: node, node: 4}", 9},
      {"failure: {line: 3, time: 0.5, mode: anchor}", 8}};
  for (const auto& [failure, chains] : cases) {
    scenarios::Scenario scenario = testing::SeedVesselScenario(failure);
    for (auto& line : scenario.mooring.lines) line.sections.front().segments = 10;
    Simulation sim(scenarios::ToPlantModel(scenario), 1);
    sim.AdvanceTo(1.0);
    SCOPED_TRACE(failure);
    ASSERT_NE(sim.system().Blocks(), nullptr);
    EXPECT_EQ(sim.system().Blocks()->chains.size(), chains);
    CheckBlockSolve(sim, AwayFromRest(sim), 1.0);
  }
}

// The bridled library mooring: the apex's states join the vessel's in the border, the
// legs hang from it to the turret (chains coupled to the border at both ends), the ground
// line rises to it.
TEST(CoupledJacobian, AFreePointInTheBorder) {
  scenarios::Scenario scenario =
      scenarios::LoadScenario(MOORSIM_SOURCE_DIR "/scenarios/library/seed_bridled.yaml");
  scenario.environment = {};  // still water, as in the tests above (the sea's hull loads
                              // are the plant's own)
  for (auto& line : scenario.mooring.lines) {
    line.sections.front().segments = std::min(line.sections.front().segments, 10);
  }
  Simulation sim(scenarios::ToPlantModel(scenario), 1);
  ASSERT_NE(sim.system().Blocks(), nullptr);
  EXPECT_EQ(sim.system().Blocks()->border, sim.plant().StateSize() + 6);
  CheckJacobian(sim, AwayFromRest(sim), 10.0);
  CheckBlockSolve(sim, AwayFromRest(sim), 10.0);
}

// The visco-elastic composite library mooring: the top segments' creep stretches load the
// vessel and are stretched by it; no block structure (KLU).
TEST(CoupledJacobian, ViscoElasticTopSegments) {
  scenarios::Scenario scenario =
      scenarios::LoadScenario(MOORSIM_SOURCE_DIR "/scenarios/library/composite_viscoelastic.yaml");
  scenario.environment = {};
  scenario.mooring.current = {};
  for (auto& line : scenario.mooring.lines) {
    // A few segments a section, the rope at the top: its creep couples to the vessel.
    line.sections = {{"chain_seed", 400.0, 3}, {"polyester", 1800.0, 5}};
    line.joints.clear();
  }
  Simulation sim(scenarios::ToPlantModel(scenario), 1);
  EXPECT_EQ(sim.system().Blocks(), nullptr);
  CheckJacobian(sim, AwayFromRest(sim), 10.0);
}

// A turret on its bearing adds two states (angle, rate) after the thrust; the fairleads
// turn with it. Free with damping, and friction both slipping (relative rate twice the
// regularisation rate) and nearly stuck (a tenth of it); the turret off the reference point.
struct TurretCase {
  const char* name;
  const char* turret;
  double relative_rate;  // Omega - r [rad/s]
};

class TurretJacobian : public ::testing::TestWithParam<TurretCase> {};

TEST_P(TurretJacobian, MatchesFiniteDifferences) {
  scenarios::Scenario scenario =
      testing::SeedVesselScenario("", std::string("  turret: ") + GetParam().turret + "\n");
  for (auto& line : scenario.mooring.lines) {
    line.sections.front().segments = 10;
    line.fairlead_body.x() += 30.0;
    line.fairlead_body.y() += 2.0;
  }
  scenario.vessel->turret.x = 30.0;
  scenario.vessel->turret.y = 2.0;
  Simulation sim(scenarios::ToPlantModel(scenario), 1);
  ASSERT_TRUE(sim.plant().turret_turns());
  CheckJacobian(sim, AwayFromRest(sim, GetParam().relative_rate), 10.0);
  CheckBlockSolve(sim, AwayFromRest(sim, GetParam().relative_rate), 10.0);
}

INSTANTIATE_TEST_SUITE_P(
    Bearings, TurretJacobian,
    ::testing::Values(TurretCase{"Free", "{bearing: free, damping: 1.0e9}", 0.003},
                      TurretCase{"FrictionSlipping",
                                 "{bearing: friction, friction_coefficient: 0.02, "
                                 "slip_rate: 1.0e-3}",
                                 2.0e-3},
                      TurretCase{"FrictionNearlyStuck",
                                 "{bearing: friction, friction_coefficient: 0.02, "
                                 "slip_rate: 1.0e-3}",
                                 1.0e-4}),
    [](const ::testing::TestParamInfo<TurretCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace moorsim::simulation
