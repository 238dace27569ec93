// The vessel model alone on CVODE (no loads), and the free-decay period of one DOF.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/integrator.h"
#include "core/ode_system.h"
#include "vessel/vessel_model.h"

namespace moorsim::vessel::testing {

// State [eta, nu], dense 12x12 Jacobian.
class FreeVessel : public OdeSystem {
 public:
  explicit FreeVessel(const VesselModel& model) : model_(model) {
    pattern_.size = 12;
    pattern_.row_start.push_back(0);
    for (int r = 0; r < 12; ++r) {
      for (int c = 0; c < 12; ++c) pattern_.column.push_back(c);
      pattern_.row_start.push_back(static_cast<int64_t>(pattern_.column.size()));
    }
  }
  int StateSize() const override { return 12; }
  void Derivatives(double, const double* x, double* xdot) override {
    Vec6 eta_dot, nu_dot;
    model_.Derivatives(Vec6(x), Vec6(x + 6), Vec6::Zero(), &eta_dot, &nu_dot);
    Eigen::Map<Vec6> eta_out(xdot), nu_out(xdot + 6);
    eta_out = eta_dot;
    nu_out = nu_dot;
  }
  const SparsityPattern& JacobianPattern() const override { return pattern_; }
  void Jacobian(double, const double* x, const double*, double* values) override {
    const VesselModel::Jacobian J = model_.Jacobians(Vec6(x), Vec6(x + 6));
    Eigen::Matrix<double, 12, 12> full;
    full << J.J_etadot_eta, J.J_etadot_nu, J.J_nudot_eta, J.J_nudot_nu;
    for (int r = 0; r < 12; ++r) {
      for (int c = 0; c < 12; ++c) values[12 * r + c] = full(r, c);
    }
  }

 private:
  const VesselModel& model_;
  SparsityPattern pattern_;
};

// Mean period between upward zero crossings of state component `k` over `duration`,
// starting from eta0 at rest; optionally |E_end - E_0| / E_0.
inline double DecayPeriod(const VesselModel& model, const Vec6& eta0, int k, double duration,
                          double* energy_change = nullptr) {
  FreeVessel sys(model);
  std::vector<double> x(12, 0.0);
  for (int i = 0; i < 6; ++i) x[i] = eta0(i);
  IntegratorOptions o;
  o.rtol = 1e-9;
  o.atol.assign(12, 1e-10);
  o.max_order = 5;
  Integrator integrator(sys, 0.0, x.data(), o);
  const double e0 = model.Energy(eta0, Vec6::Zero());
  double previous = x[k], t_prev = 0.0;
  std::vector<double> crossings;
  const double dt = 0.02;
  for (int i = 1; i <= static_cast<int>(duration / dt); ++i) {
    integrator.AdvanceTo(dt * i);
    const double value = integrator.state()[k];
    if (previous < 0.0 && value >= 0.0) {
      crossings.push_back(t_prev + dt * (-previous) / (value - previous));
    }
    previous = value;
    t_prev = dt * i;
  }
  if (energy_change != nullptr) {
    const double e1 = model.Energy(Vec6(integrator.state()), Vec6(integrator.state() + 6));
    *energy_change = std::abs(e1 - e0) / e0;
  }
  if (crossings.size() < 2) return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

}  // namespace moorsim::vessel::testing
