// A thin RAII adapter over SUNDIALS CVODE (variable-order BDF, Newton iteration) with the
// block solver of core/block_solver.h (or the KLU sparse direct solver) and an analytic
// Jacobian supplied by an OdeSystem.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/choice.h"
#include "core/ode_system.h"

namespace moorsim {

struct IntegratorOptions {
  double rtol = 1e-4;
  std::vector<double> atol;  ///< per state component; size must equal the state size
  /// If not empty, rtol applies to |x - reference| instead of |x|: error weights are
  /// 1 / (rtol |x_i - reference_i| + atol_i). For positions this makes rtol relative to a
  /// node's displacement rather than to its distance from the field origin (with plain
  /// weights, rtol 1e-4 on a node 2 km away allows 0.2 m of error, which is 1 MN of
  /// tension error in a 45 m chain segment).
  std::vector<double> reference;
  int max_order = 5;  ///< BDF order cap, 1..5
  bool stability_limit_detection = true;
  double max_step = 0.0;  ///< [s], 0 = unlimited
  /// The Newton systems' solver: kBlock uses BorderedBlockSolver when the system describes
  /// its block structure (OdeSystem::Blocks()) and KLU otherwise; kKlu always uses KLU.
  enum class LinearSolver { kBlock, kKlu };
  LinearSolver linear_solver = LinearSolver::kBlock;
  long max_steps_per_call = 200000;
};

inline constexpr std::string_view kLinearSolverNames[] = {"block", "klu"};
constexpr ChoiceInfo ChoicesOf(IntegratorOptions::LinearSolver) {
  return {"linear solver", kLinearSolverNames};
}

/// Integrator counters, summed over every CVODE instance of a run (a topology change
/// creates a new one).
struct IntegratorStats {
  long steps = 0;
  long rhs_evals = 0;
  long jacobian_evals = 0;
  long linear_setups = 0;
  long newton_iterations = 0;
  long newton_failures = 0;
  long error_test_failures = 0;
  long stability_order_reductions = 0;
  double last_step = 0.0;
  int last_order = 0;
  /// Wall time [s] inside the right-hand side, the Jacobian, the linear solver's numerical
  /// factorisations (its setup) and its solves; the rest of CVODE's time is everything else.
  double rhs_seconds = 0.0;
  double jacobian_seconds = 0.0;
  double linear_setup_seconds = 0.0;
  double linear_solve_seconds = 0.0;

  IntegratorStats& operator+=(const IntegratorStats& other);
};

class Integrator {
 public:
  /// Starts CVODE at (t0, x0). Throws moorsim::Error naming the SUNDIALS call on failure.
  Integrator(OdeSystem& system, double t0, const double* x0, const IntegratorOptions& options);
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// Integrates to t_out and returns the state there (interpolated if CVODE stepped past
  /// it, never past `stop_time` if one is set). Throws SolverError with t and the flag.
  void AdvanceTo(double t_out);
  /// CVODE will not step beyond this time (used for events such as a line failure).
  void SetStopTime(double t_stop);
  /// Asked at every right-hand-side evaluation from now on (empty: never): once it returns
  /// true, AdvanceTo() stops and throws moorsim::Interrupted; the integrator must then be
  /// restarted before it is used again. It must be cheap (read a flag, look at a clock).
  void SetInterruptCheck(std::function<bool()> check);
  /// Starts over at (t0, x0), as a new Integrator of the same system and options would
  /// (the same steps, bit for bit), keeping this one's memory and the linear solver's
  /// symbolic work: microseconds instead of the new solver's set-up. The system's state
  /// layout and pattern must not have changed. `reference` replaces the tolerance
  /// reference (IntegratorOptions::reference; empty without one). Counters start at zero.
  void Restart(double t0, const double* x0, const std::vector<double>& reference);

  double time() const { return t_; }
  const double* state() const;
  int size() const { return n_; }
  IntegratorStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int n_ = 0;
  double t_ = 0.0;
};

}  // namespace moorsim
