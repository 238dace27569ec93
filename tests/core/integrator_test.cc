// The CVODE adapter (KLU here: these systems have no block structure) on systems with known
// solutions, and its failure reporting.
#include "core/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace moorsim {
namespace {

// M independent damped oscillators x'' + 2 zeta w x' + w^2 x = 0, state [x, v] per
// oscillator: a sparse system (2x2 blocks) with a closed-form solution.
class Oscillators : public OdeSystem {
 public:
  Oscillators(int count, double zeta) : count_(count), zeta_(zeta) {
    pattern_.size = 2 * count;
    pattern_.row_start.push_back(0);
    for (int i = 0; i < count; ++i) {
      for (int r = 0; r < 2; ++r) {
        pattern_.column.push_back(2 * i);
        pattern_.column.push_back(2 * i + 1);
        pattern_.row_start.push_back(static_cast<int64_t>(pattern_.column.size()));
      }
    }
  }
  double omega(int i) const { return 1.0 + 0.5 * i; }
  int StateSize() const override { return 2 * count_; }
  void Derivatives(double t, const double* x, double* xdot) override {
    ++calls;
    if (t > fail_after) throw std::runtime_error("model gave up");
    for (int i = 0; i < count_; ++i) {
      const double w = omega(i);
      xdot[2 * i] = x[2 * i + 1];
      xdot[2 * i + 1] = -w * w * x[2 * i] - 2.0 * zeta_ * w * x[2 * i + 1];
      if (t > nan_after) xdot[2 * i + 1] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  const SparsityPattern& JacobianPattern() const override { return pattern_; }
  void Jacobian(double, const double*, const double*, double* values) override {
    for (int i = 0; i < count_; ++i) {
      const double w = omega(i);
      double* v = values + 4 * i;
      v[0] = 0.0;
      v[1] = 1.0;
      v[2] = -w * w;
      v[3] = -2.0 * zeta_ * w;
    }
  }
  // Exact x(t) for x(0) = 1, v(0) = 0 (underdamped).
  double Exact(int i, double t) const {
    const double w = omega(i);
    const double wd = w * std::sqrt(1.0 - zeta_ * zeta_);
    return std::exp(-zeta_ * w * t) * (std::cos(wd * t) + zeta_ * w / wd * std::sin(wd * t));
  }
  double fail_after = std::numeric_limits<double>::infinity();
  double nan_after = std::numeric_limits<double>::infinity();
  long calls = 0;

 private:
  int count_;
  double zeta_;
  SparsityPattern pattern_;
};

IntegratorOptions Options(int n, double rtol, double atol) {
  IntegratorOptions o;
  o.rtol = rtol;
  o.atol.assign(n, atol);
  return o;
}

std::vector<double> Start(int count) {
  std::vector<double> x(2 * count, 0.0);
  for (int i = 0; i < count; ++i) x[2 * i] = 1.0;
  return x;
}

TEST(Integrator, DampedOscillatorsMatchTheClosedForm) {
  Oscillators sys(5, 0.05);
  const std::vector<double> x0 = Start(5);
  Integrator integrator(sys, 0.0, x0.data(), Options(10, 1e-8, 1e-10));
  integrator.AdvanceTo(10.0);
  EXPECT_DOUBLE_EQ(integrator.time(), 10.0);
  for (int i = 0; i < 5; ++i) {
    // Global error of a tolerance-1e-8 BDF run over ~16 periods: a few 1e-7.
    EXPECT_NEAR(integrator.state()[2 * i], sys.Exact(i, 10.0), 2e-6) << "oscillator " << i;
  }
  const IntegratorStats s = integrator.stats();
  EXPECT_GT(s.steps, 10);
  EXPECT_GE(s.rhs_evals, s.steps);
  EXPECT_GT(s.jacobian_evals, 0);
  EXPECT_GT(s.newton_iterations, 0);
  EXPECT_GE(s.last_order, 1);
}

TEST(Integrator, ToleranceReferenceIsUsedAndChecked) {
  Oscillators sys(2, 0.1);
  const std::vector<double> x0 = Start(2);
  IntegratorOptions o = Options(4, 1e-6, 1e-9);
  o.reference = {1.0, 0.0, 1.0, 0.0};
  Integrator integrator(sys, 0.0, x0.data(), o);
  integrator.AdvanceTo(5.0);
  EXPECT_NEAR(integrator.state()[0], sys.Exact(0, 5.0), 1e-4);
  o.reference = {1.0};
  EXPECT_THROW(Integrator(sys, 0.0, x0.data(), o), Error);
}

TEST(Integrator, StopTimeIsNeverPassed) {
  Oscillators sys(3, 0.05);
  const std::vector<double> x0 = Start(3);
  Integrator integrator(sys, 0.0, x0.data(), Options(6, 1e-6, 1e-9));
  integrator.SetStopTime(1.2345);
  sys.fail_after = 1.2345;  // any evaluation beyond the stop time would throw
  integrator.AdvanceTo(1.2345);
  EXPECT_DOUBLE_EQ(integrator.time(), 1.2345);
}

// Runs three oscillators to 5 s and returns the SolverError's message ("" if none).
std::string FailureMessage(Oscillators& sys) {
  const std::vector<double> x0 = Start(3);
  Integrator integrator(sys, 0.0, x0.data(), Options(6, 1e-6, 1e-9));
  try {
    integrator.AdvanceTo(5.0);
  } catch (const SolverError& e) {
    return e.what();
  }
  return "";
}

TEST(Integrator, ModelFailureBecomesSolverErrorWithTimeAndFlag) {
  Oscillators sys(3, 0.05);
  sys.fail_after = 2.0;
  const std::string what = FailureMessage(sys);
  // The time named is the last one CVODE reached: just before the model failed at 2 s.
  const std::size_t at = what.find("t = ");
  ASSERT_NE(at, std::string::npos) << what;
  const double t = std::stod(what.substr(at + 4));
  EXPECT_GT(t, 1.5) << what;
  EXPECT_LE(t, 2.0) << what;
  EXPECT_NE(what.find("CVODE flag"), std::string::npos) << what;
  EXPECT_NE(what.find("model gave up"), std::string::npos) << what;
}

TEST(Integrator, NonFiniteDerivativeIsRetriedThenReported) {
  Oscillators sys(3, 0.05);
  sys.nan_after = 1.0;
  const std::string what = FailureMessage(sys);
  EXPECT_NE(what.find("non-finite"), std::string::npos) << what;
  EXPECT_NE(what.find("CV_"), std::string::npos) << what;  // the flag's name
}

TEST(Integrator, RejectsMismatchedTolerances) {
  Oscillators sys(2, 0.1);
  const std::vector<double> x0 = Start(2);
  EXPECT_THROW(Integrator(sys, 0.0, x0.data(), Options(3, 1e-6, 1e-9)), Error);
}

}  // namespace
}  // namespace moorsim
