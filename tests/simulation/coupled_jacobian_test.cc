// The coupled system's analytic Jacobian (vessel + lines + coupling blocks) against central
// finite differences of its own right-hand side, over the whole state.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/simulation/test_scenarios.h"
#include "tools/simulation/simulation.h"

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

TEST(CoupledJacobian, MatchesFiniteDifferencesAwayFromRest) {
  scenarios::Scenario scenario = testing::SeedVesselScenario();
  for (auto& line : scenario.mooring.lines) line.segments = 10;  // a small system, same blocks
  Simulation sim(scenario, 1);
  std::vector<double> x = sim.state();
  // A pose away from rest in all six DOFs, body velocities, thrust and node velocities.
  const double offset[6] = {3.0, -2.0, 0.2, 0.01, -0.008, 0.05};
  const double velocity[6] = {0.3, -0.2, 0.05, 0.004, -0.003, 0.002};
  for (int i = 0; i < 6; ++i) {
    x[i] += offset[i];
    x[6 + i] = velocity[i];
  }
  for (int k = 12; k < 15; ++k) x[k] = 2e5 * (k - 11);
  for (std::size_t i = 15; i < x.size(); i += 6) {
    for (int c = 3; c < 6; ++c) x[i + c] = 0.05 * std::sin(0.37 * i + c);
  }
  CheckJacobian(sim, x, 10.0);
}

}  // namespace
}  // namespace moorsim::simulation
